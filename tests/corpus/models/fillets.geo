// An L-shaped bracket with a bolt hole: two of its edges filleted, the outer
// vertical edges chamfered (sharp and smooth model edges side by side).
SetFactory("OpenCASCADE");
Box(1) = {0, 0, 0, 1.5, 1, 0.3};
Box(2) = {0, 0, 0.3, 0.3, 1, 0.9};
BooleanUnion(3) = { Volume{1}; Delete; }{ Volume{2}; Delete; };
Cylinder(4) = {0.9, 0.5, -0.1, 0, 0, 0.5, 0.18};
BooleanDifference(5) = { Volume{3}; Delete; }{ Volume{4}; Delete; };
// The inner corner edge (x = 0.3, z = 0.3) and the top edge of the upright.
e1() = Curve In BoundingBox{0.29, -0.01, 0.29, 0.31, 1.01, 0.31};
e2() = Curve In BoundingBox{-0.01, -0.01, 1.19, 0.01, 1.01, 1.21};
v() = Fillet{5}{e1(0), e2(0)}{0.08};
// The two outer vertical edges at x = 1.5.
e3() = Curve In BoundingBox{1.49, -0.01, -0.01, 1.51, 0.01, 0.31};
e4() = Curve In BoundingBox{1.49, 0.99, -0.01, 1.51, 1.01, 0.31};
f() = Surface In BoundingBox{1.49, -0.01, -0.01, 1.51, 1.01, 0.31};
Chamfer{v(0)}{e3(0), e4(0)}{f(0), f(0)}{0.1}

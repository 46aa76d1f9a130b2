// A six-pointed star prism with a hexagonal pocket in its top and a round
// boss on its bottom: sharp convex and concave model edges and corners of
// every angle (a CAD-like surface for TetGen).
SetFactory("OpenCASCADE");
n = 6;
For i In {0:2*n-1}
  r = (i % 2 == 0) ? 1.0 : 0.55;
  Point(1+i) = {r*Cos(i*Pi/n), r*Sin(i*Pi/n), 0};
EndFor
For i In {0:2*n-1}
  Line(1+i) = {1+i, 1+(i+1)%(2*n)};
EndFor
Curve Loop(1) = {1:2*n};
Plane Surface(1) = {1};
e() = Extrude{0, 0, 0.35}{ Surface{1}; };
For i In {0:5}
  Point(100+i) = {0.3*Cos(i*Pi/3), 0.3*Sin(i*Pi/3), 0.2};
EndFor
For i In {0:5}
  Line(100+i) = {100+i, 100+(i+1)%6};
EndFor
Curve Loop(100) = {100:105};
Plane Surface(100) = {100};
p() = Extrude{0, 0, 0.3}{ Surface{100}; };
BooleanDifference(20) = { Volume{e(1)}; Delete; }{ Volume{p(1)}; Delete; };
Cylinder(21) = {0, 0, -0.25, 0, 0, 0.26, 0.2};
BooleanUnion(22) = { Volume{20}; Delete; }{ Volume{21}; Delete; };

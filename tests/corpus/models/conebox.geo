// A cone standing on a box, with a hole through the box: a thick solid with
// a sharp apex, a circular edge where the cone meets the box and a bore.
SetFactory("OpenCASCADE");
Cone(1) = {0, 0, 0, 0, 0, 1.5, 0.5, 0};
Box(2) = {-0.6, -0.6, -0.4, 1.2, 1.2, 0.4};
BooleanUnion(3) = { Volume{2}; Delete; }{ Volume{1}; Delete; };
Cylinder(4) = {0.3, 0.3, -0.5, 0, 0, 0.6, 0.08};
BooleanDifference(5) = { Volume{3}; Delete; }{ Volume{4}; Delete; };

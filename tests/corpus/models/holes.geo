// A block with a cylindrical through-hole along y, a blind cylindrical hole
// from the top, and a spherical cavity cut into a corner.
SetFactory("OpenCASCADE");
Box(1) = {0, 0, 0, 2, 1, 1};
Cylinder(2) = {0.5, -0.1, 0.5, 0, 1.2, 0, 0.22};
Cylinder(3) = {1.4, 0.5, 0.45, 0, 0, 0.7, 0.15};
Sphere(4) = {2, 1, 1, 0.3};
BooleanDifference{ Volume{1}; Delete; }{ Volume{2:4}; Delete; }

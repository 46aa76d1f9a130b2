// A box with six small spherical inclusions of different radii, fragmented so
// that every sphere is a material of its own (curved interfaces, coarse at
// Gmsh's default size).
SetFactory("OpenCASCADE");
Box(1) = {0, 0, 0, 1.2, 1, 0.8};
Sphere(2) = {0.25, 0.25, 0.25, 0.09};
Sphere(3) = {0.85, 0.3, 0.5, 0.12};
Sphere(4) = {0.45, 0.7, 0.35, 0.07};
Sphere(5) = {0.95, 0.75, 0.2, 0.1};
Sphere(6) = {0.3, 0.55, 0.6, 0.08};
Sphere(7) = {0.6, 0.2, 0.6, 0.07};
BooleanFragments{ Volume{1}; Delete; }{ Volume{2:7}; Delete; }

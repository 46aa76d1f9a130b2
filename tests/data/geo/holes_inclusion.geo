// A box with two spherical holes and a material inclusion.
SetFactory("OpenCASCADE");
Box(1) = {0, 0, 0, 1, 1, 1};
Sphere(2) = {0.3, 0.3, 0.3, 0.15};
Sphere(3) = {0.7, 0.7, 0.6, 0.2};
Box(4) = {0.55, 0.1, 0.1, 0.3, 0.3, 0.3};
BooleanDifference{ Volume{1}; Delete; }{ Volume{2, 3}; Delete; }
BooleanFragments{ Volume{1}; Delete; }{ Volume{4}; Delete; }
Mesh.MeshSizeMax = 0.07;

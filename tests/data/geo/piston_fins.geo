// A cylinder with two zero-thickness fins attached to its wall along a line.
SetFactory("OpenCASCADE");
Cylinder(1) = {0, 0, 0, 0, 0, 2, 1};
Rectangle(10) = {0.4, -0.01, 0.3, 0.8, 1.2};
Rotate {{1, 0, 0}, {0, 0, 0.3}, Pi/2} { Surface{10}; }
Rectangle(11) = {-1.2, 0.0, 1.0, 0.8, 0.7};
Rotate {{1, 0, 0}, {0, 0, 1.0}, Pi/2} { Surface{11}; }
BooleanFragments{ Volume{1}; Delete; }{ Surface{10, 11}; Delete; }
Mesh.MeshSizeMax = 0.12;

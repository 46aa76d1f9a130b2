// A block with three crossing fractures, one crossing the outer boundary.
SetFactory("OpenCASCADE");
Box(1) = {0, 0, 0, 2, 1, 1};
Rectangle(10) = {0.3, 0.2, 0.5, 1.2, 0.6};
Rectangle(11) = {0.5, 0.1, 0.1, 0.8, 0.8};
Rotate {{1, 0, 0}, {0.9, 0.5, 0.5}, Pi/2} { Surface{11}; }
Rectangle(12) = {0.8, -0.3, 0.2, 1.6, 0.6};
Rotate {{0, 1, 0}, {1.2, 0.0, 0.5}, Pi/3} { Surface{12}; }
BooleanFragments{ Volume{1}; Delete; }{ Surface{10, 11, 12}; Delete; }
Point(100) = {1.8, 0.9, 0.9};  // a construction point
Mesh.MeshSizeMax = 0.08;

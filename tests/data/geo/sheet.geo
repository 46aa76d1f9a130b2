// A box fragmented with a larger internal sheet: the sheet's part inside the
// box is a fracture of the volume, its parts outside stay in the model as
// free surfaces (with their own curves and points).
SetFactory("OpenCASCADE");
Box(1) = {0, 0, 0, 1, 1, 1};
Rectangle(10) = {-0.5, -0.5, 0.5, 2, 2};
BooleanFragments{ Volume{1}; Delete; }{ Surface{10}; Delete; }
Mesh.MeshSizeMax = 0.4;

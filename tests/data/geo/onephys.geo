// Two boxes sharing a face, only the left one in a physical group: without
// -save_all Gmsh writes no tet of the right box.
SetFactory("OpenCASCADE");
Box(1) = {0, 0, 0, 1, 1, 1};
Box(2) = {1, 0, 0, 1, 1, 1};
Coherence;
Physical Volume("left") = {1};
Mesh.MeshSizeMax = 0.5;

// A torus: a thick solid with one smooth curved face and no sharp edge.
// TetGen's -pY meshes it from the surface points alone, every tet reaching
// across the tube (the case of optim/steiner.h).
SetFactory("OpenCASCADE");
Torus(1) = {0, 0, 0, 0.7, 0.3};

// The unit ball (OpenCASCADE): its surface has a seam curve and two curves
// collapsed to the poles.
SetFactory("OpenCASCADE");
Sphere(1) = {0, 0, 0, 1};
Mesh.MeshSizeMax = 0.6;

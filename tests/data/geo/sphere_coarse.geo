SetFactory("OpenCASCADE");
Sphere(1) = {0,0,0,1};
// Coarse: 78 tets, 42 dual cells whose worst cell the min-max descent cannot settle.
Mesh.MeshSizeMax = 3;
Mesh.MinimumCirclePoints = 7;

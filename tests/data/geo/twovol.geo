// Two unit boxes sharing a face (an interface), with physical groups for both
// volumes, the interface and the outer end faces.
SetFactory("OpenCASCADE");
Box(1) = {0, 0, 0, 1, 1, 1};
Box(2) = {1, 0, 0, 1, 1, 1};
Coherence;
Physical Volume("left") = {1};
Physical Volume("right") = {2};
Physical Surface("interface") = {2};
Physical Surface("ends") = {1, 7};
Mesh.MeshSizeMax = 0.5;

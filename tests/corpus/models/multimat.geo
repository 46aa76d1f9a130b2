// A fragmented multi-material model: a plate, a cylinder through it, a sphere
// overlapping both and a small box at a corner; BooleanFragments gives every
// overlap a region of its own (curved and flat interfaces, triple curves).
SetFactory("OpenCASCADE");
Box(1) = {0, 0, 0, 1, 1, 0.4};
Cylinder(2) = {0.5, 0.5, -0.2, 0, 0, 0.8, 0.25};
Sphere(3) = {0.7, 0.6, 0.4, 0.2};
Box(4) = {0.75, -0.05, 0.2, 0.3, 0.3, 0.3};
BooleanFragments{ Volume{1}; Delete; }{ Volume{2:4}; Delete; }

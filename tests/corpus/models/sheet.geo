// A box cut by two internal sheets (fractures): a tilted disk that ends
// inside the box on all sides, and a rectangle that meets the top face and
// ends inside along its other three sides.
SetFactory("OpenCASCADE");
Box(1) = {0, 0, 0, 1.5, 1, 1};
Disk(10) = {0.5, 0.5, 0.45, 0.3};
Rotate {{1, 1, 0}, {0.5, 0.5, 0.45}, Pi/5} { Surface{10}; }
Rectangle(11) = {0.9, 0.2, 0.35, 0.45, 0.65};
Rotate {{1, 0, 0}, {0.9, 0.2, 0.35}, Pi/2} { Surface{11}; }
Translate {0, 0.3, 0} { Surface{11}; }
BooleanFragments{ Volume{1}; Delete; }{ Surface{10, 11}; Delete; }

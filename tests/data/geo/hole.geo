// A box with a cylindrical hole (built-in kernel): the circle arcs have a
// centre point, point 1, that no tet uses (a construction point).
lc = 0.3;
Point(1) = {0.5, 0.5, 0, lc};
Point(2) = {0, 0, 0, lc}; Point(3) = {1, 0, 0, lc}; Point(4) = {1, 1, 0, lc}; Point(5) = {0, 1, 0, lc};
Point(6) = {0.75, 0.5, 0, lc}; Point(7) = {0.5, 0.75, 0, lc}; Point(8) = {0.25, 0.5, 0, lc}; Point(9) = {0.5, 0.25, 0, lc};
Line(1) = {2, 3}; Line(2) = {3, 4}; Line(3) = {4, 5}; Line(4) = {5, 2};
Circle(5) = {6, 1, 7}; Circle(6) = {7, 1, 8}; Circle(7) = {8, 1, 9}; Circle(8) = {9, 1, 6};
Curve Loop(1) = {1, 2, 3, 4}; Curve Loop(2) = {5, 6, 7, 8};
Plane Surface(1) = {1, 2};
Extrude {0, 0, 0.6} { Surface{1}; }
// A free curve bounding no volume, away from the box.
Point(100) = {2, 0, 0, lc}; Point(101) = {2, 1, 0, lc};
Line(100) = {100, 101};

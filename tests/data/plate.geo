// A plate with a hole: the fixture for the Gmsh readers (points, lines and triangles, several entities).
SetFactory("OpenCASCADE");
Rectangle(1) = {0, 0, 0, 2, 1};
Disk(2) = {0.7, 0.5, 0, 0.2};
BooleanDifference{ Surface{1}; Delete; }{ Surface{2}; Delete; }
Mesh.CharacteristicLengthMax = 0.05;

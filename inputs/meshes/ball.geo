// Source of ball.msh: gmsh -3 ball.geo -o ball.msh (Gmsh 4.8.4).
// Solid ball of radius 0.2 centred at the origin, physical volume "ball", surface "surface".
SetFactory("OpenCASCADE");
Sphere(1) = {0, 0, 0, 0.2};
Physical Volume("ball") = {1};
Physical Surface("surface") = {1};
Mesh.MeshSizeMax = 0.07;
Mesh.MshFileVersion = 4.1;
General.NumThreads = 1;

// Flat die: a plate whose lower face touches the ring's top (z = 5 mm), in mm.
SetFactory("OpenCASCADE");
Box(1) = {-2, -2, 5, 24, 24, 3};

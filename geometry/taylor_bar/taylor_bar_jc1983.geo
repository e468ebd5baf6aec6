// The OFHC copper cylinder of Johnson & Cook's (1983) impact tests: 7.62 mm across (0.3 in), 25.4 mm
// long (1 in); the quarter model of taylor_bar.geo at that size, in mm.
R = 3.81;
L = 25.4;
Include "taylor_bar.geo";

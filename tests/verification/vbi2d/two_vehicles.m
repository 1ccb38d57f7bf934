% Two vehicles in opposite directions on a 25 m simply supported beam (VBI-2D, coupled solver).
% Vehicle 1: VBI-2D's two-axle vehicle of E01_Example.m (Vehicle_2), driving -x at 70 km/h.
% Vehicle 2: VBI-2D's five-axle vehicle of E01_Example.m (Vehicle_2A3), driving +x at 90 km/h.
% Smooth road, undamped beam (so that Rayleigh vs modal damping plays no part), constant speeds.
clear; clc;
here = pwd; addpath(fullfile(here, 'shims')); addpath(fullfile(here, 'Functions'));
Beam.Prop.type = 0; Beam.Prop.Lb = 25; Beam.Prop.rho = 18358; Beam.Prop.E = 3.5e10;
Beam.Prop.I = 1.3901; Beam.Prop.A = 1; Beam.Prop.damp_per = 0;
Beam.BC.loc = [0,Beam.Prop.Lb]; Beam.BC.vert_stiff = [Inf,Inf]; Beam.BC.rot_stiff = [0,0];
Beam.Mesh.Ele.num = 100;
veh_num = 1;
Veh(veh_num).Model.type = 'Vehicle_2';
Veh(veh_num).Prop.mBi = 10500; Veh(veh_num).Prop.IBi = 50000;
Veh(veh_num).Prop.kSj = [1,1]*6e6; Veh(veh_num).Prop.cSj = [1,1]*1e4;
Veh(veh_num).Prop.mGj = [1,1]*900; Veh(veh_num).Prop.kTk = [1,1]*1.75e6; Veh(veh_num).Prop.cTk = [1,1]*0;
Veh(veh_num).Prop.dj = [-2.5, 2.5];
Veh(veh_num).Pos.x0 = Beam.Prop.Lb + 6; Veh(veh_num).Pos.vel = -70/3.6;
veh_num = 2;
Veh(veh_num).Model.type = 'Vehicle_2A3';
Veh(veh_num).Prop.mBi = [3100 20000]; Veh(veh_num).Prop.IBi = [5000 120000];
Veh(veh_num).Prop.kSj = [6000000 6000000 10000000 10000000 10000000];
Veh(veh_num).Prop.cSj = [10000 10000 20000 20000 20000];
Veh(veh_num).Prop.mGj = [750 750 1100 1100 1100];
Veh(veh_num).Prop.kTk = [1750000 1750000 3500000 3500000 3500000];
Veh(veh_num).Prop.cTk = [0 0 0 0 0];
Veh(veh_num).Prop.ai = [0, 5]; Veh(veh_num).Prop.bi = 3; Veh(veh_num).Prop.dj = [-1, 3.5, 2, 3.2, 4.4];
Veh(veh_num).Pos.x0 = -2; Veh(veh_num).Pos.vel = 90/3.6;
Calc.Profile.type = 0;
Calc.Solver.t_steps_per_second = 2000;
Calc.Opt.free_vib_seconds = 0.5;
Calc.Opt.verbose = 0;
Calc.Proc.name = 'Coupled';
A02_Calculations;
mid = Beam.Mesh.Node.at_mid_span;
t = Calc.Solver.t_beam(:);
u = Sol.Beam.U.value_xt(mid,:)';
us = Sol.Beam.U_static.value_xt(mid,:)';
F = [Sol.Veh(1).Under.onBeamF; Sol.Veh(2).Under.onBeamF]';
keep = 1:4:numel(t);
M = [t, u, us, F](keep,:);
fid = fopen('vbi2d_two_vehicles.csv','w');
fprintf(fid, '# VBI-2D (github.com/DanielCanteroNTNU/VBI-2D @ 1d36c83) run in GNU Octave by two_vehicles.m; every 4th step\n');
fprintf(fid, 'time [s],midspan_displacement [m],midspan_static_displacement [m],v1_axle1 [N],v1_axle2 [N],v2_axle1 [N],v2_axle2 [N],v2_axle3 [N],v2_axle4 [N],v2_axle5 [N]\n');
fprintf(fid, [repmat('%.10e,', 1, 9), '%.10e\n'], M');
fclose(fid);
printf('dt %.10e, n %d, t0 %.6f, max|u| %.6e, static %.6e, f1 %.6f Hz\n', Calc.Solver.dt, numel(t), t(1), max(abs(u)), max(abs(us)), Beam.Modal.f(1));

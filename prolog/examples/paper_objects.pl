% The example of section 2.2 of the paper: a Poisson number of objects with
% uniform positions that drift by +3 per step, and left/2 between them.
% (The paper writes uniform(0,100) for the continuous uniform; `Sigma` is
% fixed to 1.0 here.)
n ~ poisson(6).
pos(P):0 ~ uniform(0, 100) := n ~= N, between(1, N, P).
pos(P):t+1 ~ gaussian(X + 3, 1.0) := pos(P):t ~= X.
left(O1, O2):t ~ finite([0.99:true, 0.01:false]) :=
    pos(O1):t ~= P1, pos(O2):t ~= P2, P1 < P2.
left(O1, O2):t ~ finite([0.0:true, 1.0:false]) :=
    pos(O1):t ~= P1, pos(O2):t ~= P2, P1 >= P2.

/*  filter_floor.pl -- the least a filter step can cost when every particle is
    sampled by Prolog code on this machine.

    Hand-written, no engine: for each of N particles and M objects, draw a 3-D
    Gaussian move (Box-Muller, as the engine's sampler) and add the log density
    of an observed position.  This is only the arithmetic that the benchmark's
    model needs for perceived objects, with no logic (no clauses, no store, no
    occluder choice), so any engine that samples particles one by one in
    SWI-Prolog costs at least this much per step.

        swipl bench/filter_floor.pl 1000 10      % prints {"floor_ms_per_step": x}
*/

:- initialization(main, main).

gauss(X) :-
    U1 is 1.0 - random_float,
    U2 is random_float,
    X is sqrt(-2*log(U1))*cos(2*pi*U2).

object_step(p(X, Y, Z), o(OX, OY, OZ), p(X1, Y1, Z1), LW0, LW) :-
    gauss(A), gauss(B), gauss(C),
    X1 is X + 0.005*A, Y1 is Y + 0.005*B, Z1 is Z + 0.005*C,
    LW is LW0 - ((X1-OX)**2 + (Y1-OY)**2 + (Z1-OZ)**2)/(2*0.0004).

particle_step([], [], [], LW, LW).
particle_step([P|Ps], [O|Os], [P1|P1s], LW0, LW) :-
    object_step(P, O, P1, LW0, LW1),
    particle_step(Ps, Os, P1s, LW1, LW).

filter_step([], _, [], []).
filter_step([P|Ps], Obs, [P1|P1s], [LW|LWs]) :-
    particle_step(P, Obs, P1, 0.0, LW),
    filter_step(Ps, Obs, P1s, LWs).

run_steps(0, _, _) :- !.
run_steps(K, Ps, Obs) :-
    filter_step(Ps, Obs, Ps1, _),
    K1 is K - 1,
    run_steps(K1, Ps1, Obs).

main([NA, MA]) :-
    atom_number(NA, N), atom_number(MA, M),
    length(Objects, M), maplist(=(p(0.0, 0.0, 0.0)), Objects),
    length(Obs, M), maplist(=(o(0.01, 0.01, 0.01)), Obs),
    length(Particles, N), maplist(=(Objects), Particles),
    Steps = 10,
    set_random(seed(1)),
    statistics(cputime, T0),
    run_steps(Steps, Particles, Obs),
    statistics(cputime, T1),
    Ms is 1000*(T1-T0)/Steps,
    format("{\"floor_ms_per_step\": ~4f}~n", [Ms]).

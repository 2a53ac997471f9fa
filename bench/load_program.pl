/*  load_program.pl -- what loading a large DC program costs, against consulting as many
    plain Prolog clauses.

    Loading compiles each clause once and relates clauses to each other:
    whether a later clause can define what a clause defines (its rivals),
    which derived predicates are random or clean through what they call.
    Both are near-linear in the number of clauses; this prints, for N = 1,000
    and 10,000 clauses of three shapes, the CPU ms of ddc_load/2, the CPU ms
    of consulting N plain Prolog clauses of the same size in the same run
    (the reference), their ratio, and how much 10 times the clauses cost:

        .venv/bin/swipl bench/load_program.pl

    rivals: N/2 random variables with two clauses each (x(J, A) ~ ...);
    derived: N derived clauses over 100 predicates calling each other in a
    ring; timed: N/4 objects, each with a fact, a transition, a timed
    derived atom and an untimed random variable.  Best of 3.  Then the CPU
    ms of making a batched filter (10 particles) of N/2 objects with an h:0
    and an h:t+1 clause each, against loading the same program.
*/

:- use_module('../prolog/ddc').
:- initialization(main, main).

shape(rivals).
shape(derived).
shape(timed).

%   clause_text(+Shape, +N, +I, -Text): the I-th clause(s) of a program of N.
clause_text(rivals, N, I, T) :-
    J is I mod (N // 2),
    format(atom(T), "x(~d, A) ~~ gaussian(A, 1.0) := obj(~d, A).~n", [J, I]).
clause_text(derived, _, I, T) :-
    P is I mod 100, Q is (I + 1) mod 100, I1 is I + 1,
    format(atom(T), "d~d(o~d) := d~d(o~d), object(o~d).~n", [P, I, Q, I1, I]).
clause_text(timed, _, I, T) :-
    (   I mod 4 =:= 0 -> format(atom(T), "object(o~d) := true.~n", [I])
    ;   I mod 4 =:= 1 -> format(atom(T), "pos(o~d):t+1 ~~ gaussian(P, 0.1) := pos(o~d):t ~~= P.~n", [I, I])
    ;   I mod 4 =:= 2 -> format(atom(T), "near(o~d):t+1 := pos(o~d):t+1 ~~= P, P < 1.~n", [I, I])
    ;   format(atom(T), "w~d ~~ finite([0.5:a, 0.5:b]).~n", [I])
    ).

%   plain_text(+I, -Text): a plain Prolog clause of about the same size.
plain_text(I, T) :-
    format(atom(T), "x(~d, A) :- obj(~d, A), A > 0.~n", [I, I]).

write_program(File, Gen) :-
    setup_call_cleanup(open(File, write, S),
                       forall(call(Gen, T), write(S, T)),
                       close(S)).

dc_clause(_, _, ':- dynamic((obj/2, object/1)).\n').   % facts that come from elsewhere
dc_clause(Shape, N, T) :- between(1, N, I), clause_text(Shape, N, I, T).
plain_clause(N, T) :- between(1, N, I), plain_text(I, T).

%   best_ms(+Goal, -Ms): the least CPU time of 3 runs of Goal.
best_ms(Goal, Ms) :-
    findall(T, ( between(1, 3, _),
                 garbage_collect,
                 statistics(cputime, T0), once(Goal), statistics(cputime, T1),
                 T is (T1 - T0) * 1000 ), Ts),
    min_list(Ts, Ms).

%   consult_plain(+Module, +File): a file of its own per shape and size,
%   consulted again by each repetition (a reload, as ddc_load/2 is).
consult_plain(M, File) :-
    load_files(M:File, [silent(true)]).

measure(Shape, N, Ms, RefMs) :-
    tmp_file(dc, Dc0), atom_concat(Dc0, '.pl', Dc),
    tmp_file(plain, Pl0), atom_concat(Pl0, '.pl', Pl),
    write_program(Dc, dc_clause(Shape, N)),
    write_program(Pl, plain_clause(N)),
    best_ms(ddc_load(Dc, bench_load), Ms),
    gensym(plain_reference_, M),
    best_ms(consult_plain(M, Pl), RefMs),
    delete_file(Dc), delete_file(Pl).

main :-
    format("~w~t~10| ~w~t~18| ~w~t~30| ~w~t~44| ~w~t~51| ~w~n",
           [shape, 'N', 'ddc_load ms', 'plain Prolog ms', ratio, '10x clauses cost']),
    forall(shape(Shape),
           ( measure(Shape, 1000, Ms1, Ref1),
             measure(Shape, 10000, Ms10, Ref10),
             R1 is Ms1 / max(Ref1, 0.001), R10 is Ms10 / max(Ref10, 0.001),
             Growth is Ms10 / max(Ms1, 0.001),
             format("~w~t~10| ~d~t~18| ~1f~t~30| ~1f~t~44| ~1f~n", [Shape, 1000, Ms1, Ref1, R1]),
             format("~w~t~10| ~d~t~18| ~1f~t~30| ~1f~t~44| ~1f~t~51| ~1fx~n",
                    [Shape, 10000, Ms10, Ref10, R10, Growth]) )),
    format("~nbatched filter: N, filter_new ms, ddc_load ms of the same program~n"),
    forall(member(N, [1000, 10000]),
           ( filter_ms(N, FMs, LMs),
             format("~d~t~8| ~1f~t~20| ~1f~n", [N, FMs, LMs]) )).

filter_clause(N, T) :-
    H is N // 2, between(1, H, I),
    (   format(atom(T), "pos(o~d):0 ~~ gaussian(0, 0.1).~n", [I])
    ;   format(atom(T), "pos(o~d):t+1 ~~ gaussian(P, 0.1) := pos(o~d):t ~~= P.~n", [I, I])
    ).

filter_ms(N, FMs, LMs) :-
    tmp_file(filter, F0), atom_concat(F0, '.pl', File),
    write_program(File, filter_clause(N)),
    best_ms(ddc_load(File, _), LMs),
    best_ms(( filter_new(File, 10, 1, [engine(batched)], F), filter_free(F) ), FMs),
    delete_file(File).

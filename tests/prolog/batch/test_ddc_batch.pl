/*  plunit tests of the batched particle filter (prolog/ddc/batch/ddc_batch.pl and its
    modules prolog/ddc_batch_*.pl), reached through ddc.pl's filter_*
    predicates with engine(batched) or auto, and of its tables
    (prolog/ddc/batch/ddc_batch_tables.pl) directly.  The
    conformance answers (wumpus, pit world, Kalman, follow the occluder) are
    checked for both engines in tests/test_filter.py; these tests are about
    what the batched engine does on its own: its fragment, its evaluation of
    each goal kind over batches, its groups of threads, its state.
*/
:- use_module('../../../prolog/ddc').
:- use_module(library(plunit)).
:- use_module(library(lists)).
:- use_module(library(apply)).
:- use_module('../../../prolog/ddc/batch/ddc_batch_tables').
:- use_module('../../../prolog/ddc/batch/ddc_batch_col').

program(Lines, File) :-
    tmp_file_stream(text, File, S),
    forall(member(L, Lines), format(S, "~w~n", [L])),
    close(S).

values(F, Goal-Template, Values) :-
    filter_values(F, Template, Goal, Values).

:- begin_tests(ddc_batch).

%   A program outside the fragment: engine(batched) names the clause,
%   engine(auto) takes the per-particle engine.
test(outside_the_fragment_is_an_error_with_its_line) :-
    program([ 'x:0 ~ val(1).',
              'x:t+1 ~ val(Y) := x:t ~= X, sample(gaussian(X, 1.0), Y).' ], File),
    catch(filter_new(File, 10, 1, [engine(batched)], _), E, true),
    E = error(ddc(batched_unsupported(_), File:2), _),
    message_to_codes(E, Text),
    once(sub_atom(Text, _, _, _, ':2: outside what the batched filter evaluates')),
    filter_new(File, 10, 1, [engine(auto)], F),
    filter_engine(F, per_particle),
    filter_statistics(F, Stats),
    \+ memberchk(engine(batched), Stats),
    filter_step(F, [], [], _),
    filter_free(F).

message_to_codes(E, Text) :-
    message_to_codes(error, E, Codes0),
    atom_codes(Text, Codes0).

message_to_codes(Kind, E, Codes) :-
    '$messages':translate_message(E, Lines, []),
    with_output_to(codes(Codes), print_message_lines(current_output, kind(Kind), Lines)).

test(auto_takes_the_batched_engine_in_its_fragment) :-
    program([ 'x:0 ~ val(1).', 'x:t+1 ~ val(Y) := x:t ~= X, Y is X + 1.' ], File),
    filter_new(File, 10, 1, [], F),
    filter_engine(F, batched),
    filter_statistics(F, Stats),
    memberchk(engine(batched), Stats),
    filter_step(F, [], [], _), filter_step(F, [], [], _),
    values(F, (x:t ~= X)-X, Xs),
    forall(member(X, Xs), X =:= 3),
    filter_free(F).

%   Each kind of goal over a batch, on a model whose answers are known in
%   every particle: both engines give the same values.
test(goals_over_batches_agree_with_the_per_particle_engine) :-
    program([ 'obj(a) := true.', 'obj(b) := true.', 'obj(c) := true.',
              'size(a, 3) := true.', 'size(b, 1) := true.', 'size(c, 2) := true.',
              'k:0 ~ uniform([1, 2, 3]).',
              'k:t+1 ~ val(K) := k:t ~= K.',
              'big(O):t+1 := obj(O), size(O, S), k:t ~= K, S >= K.',
              'n:t+1 ~ val(L) := findall_forward(O, big(O):t+1, Os), sort(Os, L).',
              'kind:t+1 ~ val(V) := ( k:t ~= 1 -> V = one ; k:t ~= 2 -> V = two ; V = many ).',
              'odd:t+1 ~ val(yes) := ( k:t ~= 1 ; k:t ~= 3 ).',
              'odd:t+1 ~ val(no) := \\+ ( k:t ~= 1 ; k:t ~= 3 ).',
              'seen:t+1 ~ val(V) := observation(o) ~= V.',
              'observation(o):t+1 ~ val(V) := k:t ~= K, ( K > 1 -> V = high ; V = low ).',
              'first:t+1 ~ val(L) := k:t ~= K, findall(X, ( member(X, [1, 2, 3]), X >= K -> true ), L).',
              'pair:t+1 ~ val(P) := k:t ~= K, P = [first, K].',
              'fallback:t ~ val(unset).',
              'fallback:t+1 ~ val(set) := k:t ~= 3.' ], File),
    Template = r(K, L, V, O, S, B, Fi, Pa),
    Goal = ( k:t ~= K, n:t ~= L, kind:t ~= V, odd:t ~= O, seen:t ~= S, fallback:t ~= B,
             first:t ~= Fi, pair:t ~= Pa ),
    forall(member(Engine, [per_particle, batched]),
           ( filter_new(File, 60, 4, [engine(Engine)], F),
             filter_step(F, [observation(o) ~= high], [], LW),
             values(F, Goal-Template, Rs),
             nb_setval(Engine, Rs-LW),
             filter_free(F) )),
    nb_getval(batched, Rs-LW),
    forall(nth1(I, Rs, R),
           (   R = r(K1, L1, V1, O1, S1, B1, Fi1, Pa1),
               expected(K1, L1, V1, O1, B1),
               Pa1 == [first, K1],          % (X = Term binds X, per particle where Term differs)
               Fi1 == [K1],                 % (a condition commits to its first solution)
               S1 == high,
               nth1(I, LW, W),
               ( K1 > 1 -> W =:= 0.0 ; W < -1.0e308 )
           )),
    msort(Rs, Sorted), nb_getval(per_particle, Rs0-_), msort(Rs0, Sorted0),
    %   (the draws differ by engine, so compare the kinds of particle)
    sort(Sorted, Kinds), sort(Sorted0, Kinds0),
    Kinds == Kinds0.

expected(1, [a, b, c], one, yes, unset).
expected(2, [a, c], two, no, unset).
expected(3, [a], many, yes, set).

%   The language's arithmetic conveniences over columns: a random variable
%   as a comparison's operand, expressions as distribution parameters,
%   logistic/3 and linear/3; in both engines.
test(operands_parameters_and_statistical_models) :-
    program([ 'x:0 ~ uniform([1, 2, 3]).', 'x:t+1 ~ val(X) := x:t ~= X.',
              'big:t+1 ~ val(yes) := x:t > 1.', 'big:t+1 ~ val(no) := x:t =< 1.',
              'y:t+1 ~ gaussian(X*10, 1.0e-8) := x:t ~= X.',
              'q:t+1 ~ finite([X/3:a, 1-X/3:b]) := x:t ~= X.',
              'p:t+1 ~ val(P) := x:t ~= X, logistic([X], [2.0, -4.0], P).',
              'l:t+1 ~ val(Y) := x:t ~= X, linear([X, X], [1, 2, 0.5], Y).' ], File),
    forall(member(Engine, [per_particle, batched]),
           ( filter_new(File, 60, 8, [engine(Engine)], F),
             filter_step(F, [], [], _),
             values(F, (x:t ~= X, big:t ~= B, y:t ~= Y, q:t ~= Q, p:t ~= P, l:t ~= L)
                       -r(X, B, Y, Q, P, L), Rs),
             forall(member(r(X1, B1, Y1, Q1, P1, L1), Rs),
                    (   ( X1 > 1 -> B1 == yes ; B1 == no ),
                        abs(Y1 - 10*X1) < 1.0e-3,
                        ( X1 =:= 3 -> Q1 == a ; memberchk(Q1, [a, b]) ),
                        abs(P1 - 1/(1 + exp(-(2*X1 - 4)))) < 1.0e-12,
                        L1 =:= 3*X1 + 0.5
                    )),
             filter_free(F) )).

%   A key computed by arithmetic over a column (the key's argument is a
%   deferred expression: computed into a column to partition the batch by it).
test(a_computed_key_partitions_the_batch) :-
    program([ 'x:0 ~ uniform([1, 2]).', 'x:t+1 ~ val(X) := x:t ~= X.',
              'y(2):t+1 ~ val(a).', 'y(3):t+1 ~ val(b).',
              'z:t+1 ~ val(V) := x:t ~= X, J is X + 1, y(J):t+1 ~= V.' ], File),
    filter_new(File, 40, 2, [engine(batched)], F),
    filter_step(F, [], [], _),
    values(F, (x:t ~= X, z:t ~= Z)-(X-Z), Ps),
    memberchk(1-a, Ps), memberchk(2-b, Ps),
    forall(member(X1-Z1, Ps), ( X1 =:= 1 -> Z1 == a ; Z1 == b )),
    filter_free(F).

%   The sweep draws a head whose key reads a column (one key per value),
%   so that the next step still holds it at t.
test(a_head_key_read_from_a_column_is_swept) :-
    program([ 'k:0 ~ uniform([1, 2, 3]).', 'k:t+1 ~ val(K) := k:t ~= K.',
              'x(K):t+1 ~ val(K) := k:t ~= K.' ], File),
    filter_new(File, 30, 1, [engine(batched)], F),
    filter_step(F, [], [], _), filter_step(F, [], [], _),
    values(F, (k:t ~= K, (x(K):t-1) ~= X)-(K-X), Ps),
    \+ memberchk(none, Ps),                  % (every particle holds its x(K))
    forall(member(K1-X1, Ps), X1 == K1),
    filter_free(F).

%   The previous time stays readable after a step and after a resampling
%   (resampled when first read), and undo restores the particles.
test(previous_time_after_resampling_and_undo) :-
    program([ 'x:0 ~ uniform([1, 2, 3, 4, 5, 6, 7, 8]).',
              'x:t+1 ~ val(Y) := x:t ~= X, Y is X * 10.' ], File),
    forall(member(K, [1, 2]),
           ( filter_new(File, 8, 3, [engine(batched), threads(K)], F),
             filter_step(F, [], [], _),
             values(F, ((x:t-1) ~= X)-X, Before),
             values(F, (x:t ~= Y)-Y, Now),
             maplist([A, B]>>(B =:= A*10), Before, Now),
             Is = [7, 6, 5, 4, 3, 2, 1, 0],
             filter_resample(F, Is),
             values(F, (x:t ~= Y1)-Y1, NowR),
             values(F, ((x:t-1) ~= X1)-X1, BeforeR),
             reverse(Now, NowR), reverse(Before, BeforeR),
             filter_undo(F),
             values(F, (x:t ~= Y2)-Y2, Now2), Now2 == Now,
             filter_free(F) )).

%   Resampling across groups where a key is defined in every particle of
%   one group and absent from another (no particle of it asked for w(a)):
%   the key is open after the resampling, defined where it was drawn.
test(resampling_a_key_one_group_lacks) :-
    program([ 'b:0 ~ finite([0.5:yes, 0.5:no]).', 'b:t+1 ~ val(B) := b:t ~= B.',
              'w(K):t+1 ~ gaussian(0.0, 1.0) := b:t ~= yes, K = a.',
              'y:t+1 ~ val(V) := b:t ~= yes, w(a):t+1 ~= V.' ], File),
    findall(Seed,
            ( between(1, 40, Seed),
              filter_new(File, 4, Seed, [engine(batched), threads(2)], F),
              filter_step(F, [], [], _),
              values(F, (b:t ~= B)-B, Bs),
              values(F, (w(a):t ~= Y)-Y, Ys),
              filter_resample(F, [3, 2, 1, 0]),
              values(F, (b:t ~= B1)-B1, BsR),
              values(F, (w(a):t ~= Y1)-Y1, YsR),
              reverse(Bs, BsR), reverse(Ys, YsR),
              filter_free(F),
              Bs = [X, X, Z, Z], X \== Z ),      % (one group drew y, the other not)
            Pure),
    Pure \== [].

%   A step that fails (an observation no clause defines in some particle)
%   leaves the filter as it was, in one thread and in two; the filter goes
%   on.
test(an_error_in_a_step_changes_nothing) :-
    program([ 'pick:0 ~ finite([0.5:a, 0.5:b]).',
              'pick:t+1 ~ val(P) := pick:t ~= P.',
              'x:0 ~ uniform([1, 2, 3]).', 'x:t+1 ~ val(X) := x:t ~= X.',
              'observation(o):t+1 ~ gaussian(0.0, 1.0) := pick:t ~= a.' ], File),
    forall(member(K, [1, 2]),
           ( filter_new(File, 40, 5, [engine(batched), threads(K)], F),
             filter_step(F, [], [], _),
             Query = (pick:t ~= P, (x:t-1) ~= X),
             values(F, Query-(P-X), Before),
             catch(filter_step(F, [observation(o) ~= 0.5], [], _), E, true),
             E = error(ddc(no_observation_clause(_), _), _),
             filter_time(F, 1),
             values(F, Query-(P-X), After),
             After == Before,
             filter_step(F, [], [], _),
             filter_time(F, 2),
             filter_free(F) )).

%   Overlapping clauses: the same error as the per-particle engine's.
test(overlapping_clauses_are_an_error_as_in_the_other_engine) :-
    program([ 'x:0 ~ val(1).', 'x:t+1 ~ val(2) := x:t ~= 1.',
              'x:t+1 ~ val(3) := x:t ~= V, V > 0.' ], File),
    forall(member(Engine, [per_particle, batched]),
           ( filter_new(File, 30, 1, [engine(Engine)], F),
             catch(filter_step(F, [], [], _), E, true),
             message_to_codes(E, Text),
             nb_setval(Engine, Text),
             filter_free(F) )),
    nb_getval(per_particle, T1), nb_getval(batched, T2),
    T1 == T2,
    once(sub_atom(T2, _, _, _, ':2: two clauses define x:1')).

%   Clauses whose bodies contradict each other (s ~= a against s ~= b, G
%   against \+ G, h ~= V, V \== a against h ~= a, findall(T, G, L), L \== []
%   against findall(T, G, [])) are not checked for overlaps; the others
%   are, and an overlap is still the error.
test(contradicting_clauses_are_not_checked_for_overlaps_the_others_are) :-
    program([ ':- dynamic(on/0).',
              's:0 ~ uniform([a, b]).',
              's:t+1 ~ val(S) := s:t ~= S.',
              'x:t+1 ~ val(1) := s:t ~= a.',
              'x:t+1 ~ val(2) := s:t ~= b.',
              'z:t+1 ~ val(1) := on.',
              'z:t+1 ~ val(2) := \\+ on.',
              'u:t+1 ~ val(1) := s:t ~= S, S \\== a.',
              'u:t+1 ~ val(2) := s:t ~= a.',
              'y:t+1 ~ val(1) := s:t ~= a.',
              'y:t+1 ~ val(2) := s:t ~= S, S \\== b.',
              'w:t+1 ~ uniform(L) := s:t ~= S, findall(X, member(X, [S, c]), L), L \\== [].',
              'w:t+1 ~ val(none) := s:t ~= S, findall(X, member(X, [S, c]), []).' ], File),
    filter_new(File, 30, 1, [engine(batched)], F),
    ddc_filter:filter_engine_(F, _, M, _),
    findall(X-R, ( M:'$b_rv'(X0, next, _, _, origin(_, _, R)), functor(X0, X, _) ), Rs),
    Rs == [s-false, x-false, x-false, z-false, z-false, u-false, u-false, y-true, y-false,
           w-false, w-false],
    catch(filter_step(F, [], [], _), E, true),
    message_to_codes(E, Text),
    once(sub_atom(Text, _, _, _, 'two clauses define y:1')),
    filter_free(F).

%   Groups: the same seed and number of threads, the same particles; other
%   thread counts, other random streams.
test(groups_are_deterministic) :-
    program([ 'x:0 ~ gaussian(0.0, 1.0).', 'x:t+1 ~ gaussian(X, 0.5) := x:t ~= X.',
              'observation(y):t+1 ~ gaussian(X, 1.0) := x:t+1 ~= X.' ], File),
    run_walk(File, 2, A), run_walk(File, 2, B), run_walk(File, 1, C), run_walk(File, 3, D),
    A == B, A \== C, A \== D,
    A = Xs-_, length(Xs, 30).

run_walk(File, K, Xs-LW) :-
    filter_new(File, 30, 9, [engine(batched), threads(K)], F),
    filter_step(F, [observation(y) ~= 0.4], [], _),
    filter_step(F, [observation(y) ~= 0.9], [], LW),
    values(F, (x:t ~= X)-X, Xs),
    filter_free(F).

%   A non-ground read enumerates the variables defined at t, as in the
%   per-particle engine (ddc.pl, read_enum/4): those held, and those that
%   an h:t clause defines though nothing has drawn them yet (a ground
%   head, a head its static body grounds), in every particle.
test(non_ground_read_enumerates_the_defined_variables_as_per_particle) :-
    program([ 'b(2). b(3).',
              'a(1):t ~ finite([0.5:x, 0.5:y]).',
              'a(N):t ~ val(z) := b(N).',
              'k:0 ~ uniform([1, 2]).',
              'k:t+1 ~ val(K) := k:t ~= K.',
              'seen:t+1 ~ val(V) := k:t ~= 1, a(1):t ~= V.' ], File),
    forall(member(Engine, [per_particle, batched]),
           ( filter_new(File, 40, 3, [engine(Engine)], F),
             values(F, findall(N, a(N):t ~= _, L0)-L0, Ls0),
             filter_step(F, [], [], _),
             values(F, findall(N, a(N):t ~= _, L1)-L1, Ls1),
             values(F, findall(N-V, a(N):t ~= V, L2)-L2, Ls2),
             filter_free(F),
             forall(member(L, Ls0), L == [1, 2, 3]),
             forall(member(L, Ls1), L == [1, 2, 3]),
             forall(member(L, Ls2), ( L = [1-V1, 2-z, 3-z], memberchk(V1, [x, y]) )) )).

%   The pit world of the original DCPF after one step without a breeze:
%   the neighbours of (0,0) are free, and the cells defined at t are
%   (0,0), (0,1), (1,0) in every particle; current(h) is h:t.
test(pit_world_non_ground_reads_agree_with_the_per_particle_engine) :-
    source_file(ddc:ddc_load(_), Ddc),
    file_directory_name(Ddc, Dir),
    directory_file_path(Dir, 'examples/dc/dcpfwumpus2.pl', File),
    forall(member(Engine, [per_particle, batched]),
           ( filter_new(File, 500, 7, [engine(Engine)], F),
             filter_engine(F, Engine),
             filter_step(F, [observation(breeze) ~= false], [action(null)], LW),
             filter_holds(F, current(maze(1,0)) ~= free, Hs),
             filter_holds(F, maze(0,1):t ~= free, Hs1),
             values(F, findall((X,Y), maze(X,Y):t ~= free, L)-L, Ls),
             values(F, (current(maze(0,1)) ~= V)-V, Vs),
             filter_free(F),
             %   (the particles the observation keeps: weight 1)
             findall(I, ( nth1(I, LW, W), W =:= 0.0 ), Kept),
             length(Kept, NK), NK > 100,
             forall(member(I, Kept),
                    ( nth1(I, Hs, 1), nth1(I, Hs1, 1), nth1(I, Vs, free),
                      nth1(I, Ls, [(0,0),(0,1),(1,0)]) )),
             forall(( nth1(I, LW, W), W =\= 0.0 ), W < -1.0e308),
             forall(nth1(I, Ls, L2), memberchk((0,0), L2)) )).

%   A resampled table stays as made after the query that made it
%   backtracks (it is kept in a filter's global variable): its entries'
%   fields are linked, not bound.
test(a_resampled_table_survives_backtracking) :-
    table_new(Tab),
    col_from_list([1, 2, 3], C0),
    make_entry([column(C0), status(defined), arity(unknown)], E0),
    table_put(Tab, x, E0),
    col_from_list([a, a, a], CS0),
    make_entry([column(CS0), status(same(a)), arity(none)], S0),
    table_put(Tab, y, S0),
    functor(Holder, holder, 1),
    forall(true, ( resample_tables([Tab], [1-3, 1-2, 1-1], New),
                   nb_linkarg(1, Holder, New) )),
    arg(1, Holder, Kept),
    table_get(Kept, x, E), entry_column(E, C), col_list(C, Vs), Vs == [3, 2, 1],
    entry_status(E, defined),
    table_get(Kept, y, S), entry_column(S, CS), col_list(CS, VsS), VsS == [a, a, a],
    entry_status(S, Same), Same == same(a), entry_arity(S, A), A == none.

:- end_tests(ddc_batch).

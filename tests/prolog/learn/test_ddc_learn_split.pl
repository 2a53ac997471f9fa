/*  plunit tests of the data splitter (prolog/ddc/learn/ddc_learn_split.pl): items
    written back as the readers read them, units (connected worlds, or
    the constants of a type with their nearest neighbours), the test
    fraction, seeds, and errors that leave no file behind.
*/
:- use_module('../../../prolog/ddc/learn/ddc_learn_split').
:- use_module('../../../prolog/ddc/learn/ddc_learn_data').
:- use_module(library(plunit)).
:- use_module(library(lists)).
:- use_module(library(apply)).
:- use_module(library(readutil)).

%   data(+Lines, -File): learning data in a temporary file.
data(Lines, File) :-
    tmp_file_stream(text, File, S),
    forall(member(L, Lines), format(S, "~w~n", [L])),
    close(S).

%   outputs(-Train, -Test): two fresh output names in the temporary directory.
outputs(Train, Test) :-
    tmp_file(split_train, T0), atom_concat(T0, '.pl', Train),
    tmp_file(split_test, T1), atom_concat(T1, '.pl', Test).

split(Lines, Options, Train, Test, Stats) :-
    data(Lines, F),
    outputs(Train, Test),
    learn_split_files([F], [train(Train), test(Test)|Options], Stats).

terms(File, Ts) :-
    data_read_terms(File, own, Items),
    findall(T, member(item(T, _, _, _), Items), Ts).

%   subsequence_of_variants(+Sub, +List): Sub is List with some elements
%   left out, up to variable renaming.
subsequence_of_variants([], _).
subsequence_of_variants([X|Xs], [Y|Ys]) :-
    (   X =@= Y
    ->  subsequence_of_variants(Xs, Ys)
    ;   subsequence_of_variants([X|Xs], Ys)
    ).

%   split_error(+Goal, -Cause, -Where): Goal throws ddc_learn(Cause, Where).
split_error(G, Cause, Where) :-
    catch(( G, Cause = none, Where = none ), error(ddc_learn(Cause, Where), _), true).

message_string(E, S) :-
    '$messages':translate_message(E, Lines, []),
    with_output_to(string(S), print_message_lines(current_output, '', Lines)).

contains(S, Sub) :-
    once(sub_string(S, _, _, _, Sub)).

cleanup(Files) :-
    forall(( member(F, Files), exists_file(F) ), delete_file(F)).

%   Every item kind of the own dialect, in three independent worlds
%   (o1/o2, o3, o5/e1).
own_items([ ':- discontiguous client/1.',
            'type(distance(obj, obj):t).',
            'rv(colour(_), discrete([red, green])).',
            'learn(colour(X)).',
            'examples(occluded_by(A, B):t+1, pair(A, B)).',
            'near(A, B):t := distance(A, B):t ~= D, D < 0.1.',
            'p(X) ~ gaussian(0, 1) := q(X).',
            'helper(X, Y) :- \\+ X = Y, Y \\== \'B c\'.',
            'occluded_by(o1, o2):t+1.',
            'pos(o1):t ~= 2.3.',
            'distance(o1, o2):t ~= -0.5.',
            'colour(o2) ~= red.',
            'pair(o1, o2).',
            '0.7 :: p(o3).',
            'size(o3) ~= (1.5, -2, \'Q r\').',
            'colour(o3) ~= green.',
            'label(e1) ~ finite([0.7:a, 0.3:b]).',
            'owner(e1, o5) := true.',
            'rain ~= true.' ]).

dreaml_items([ ':- discontiguous client/1.',
               'base(client(c)).', 'base(district(d)).', 'base(gender(c, ge)).',
               'base(clientDistrict(c, d, x)).', 'base(hasAccount(c, a, x)).',
               'base(avgSalary(d, s)).',
               'thres(gender, 2, discrete, [m, f]).',
               'thres(avgSalary, 2, continuous, [\'-\', 9000, \'+\']).',
               'thres(clientDistrict, 3, continuous, []).',
               'thres(hasAccount, 3, continuous, []).',
               'randomVariableNames([gender, clientDistrict, hasAccount, avgSalary]).',
               'mode(gender, cnt, clientDistrict(+, -, true)).',
               'mode(gender, avg, (clientDistrict(+, -, true), avgSalary(+, -))).',
               'rank([clientDistrict, hasAccount, avgSalary, gender]).',
               'learn(gender, 2, 2, discrete).',
               'districtClient(D, C) :- clientDistrict(C, D, true).',
               'pick([H|_], H).', 'pick([], none).',
               'district(d1).', 'avgSalary(d1, 9500).',
               'client(c1).', 'gender(c1, m).', 'clientDistrict(c1, d1, true).',
               'hasAccount(c1, a1, true).',
               'district(d2).', 'avgSalary(d2, 8000.5).',
               'client(c2).', 'gender(c2, f).', 'clientDistrict(c2, d2, true).',
               'hasAccount(c2, a2, true).' ]).

:- begin_tests(ddc_learn_split_items).

test(every_own_item_kind_reads_back_to_the_same_term) :-
    own_items(Ls),
    data(Ls, F),
    outputs(Train, Test),
    learn_split_files([F], [train(Train), test(Test), fraction(0.3)], St),
    St.units =:= 3, St.cut =:= 0, St.both =:= 1, St.train + St.test =:= 10,
    terms(F, Orig), terms(Train, TrTs), terms(Test, TeTs),
    length(Orig, 19),
    subsequence_of_variants(TrTs, Orig),
    subsequence_of_variants(TeTs, Orig),
    %   declarations, directives, rules (items 1-8) and the fact without
    %   constants (19) are in both parts, every other fact in one
    forall(( nth1(I, Orig, O), ( I =< 8 ; I =:= 19 ) ),
           ( member(T1, TrTs), T1 =@= O, member(T2, TeTs), T2 =@= O -> true )),
    forall(( nth1(I, Orig, O), I > 8, I < 19 ),
           (   member(T1, TrTs), T1 =@= O -> \+ ( member(T2, TeTs), T2 =@= O )
           ;   member(T2, TeTs), T2 =@= O
           )),
    learn_data_load([Train], [targets(false)], D1), learn_data_free(D1),
    learn_data_load([Test], [targets(false)], D2), learn_data_free(D2),
    cleanup([F, Train, Test]).

test(written_terms_keep_their_operators_and_quotes) :-
    own_items(Ls),
    split(Ls, [fraction(0.3)], Train, Test, _),
    read_file_to_string(Train, S, []),
    contains(S, ":-discontiguous client/1."),
    contains(S, "p(X)~gaussian(0, 1):=q(X)."),
    contains(S, "Y\\=='B c'"),
    cleanup([Train, Test]).

test(dreaml_items_read_back_in_dreaml_dialect) :-
    dreaml_items(Ls),
    data(Ls, F),
    outputs(Train, Test),
    learn_split_files([F], [train(Train), test(Test), fraction(0.5), unit(d)], St),
    St.units =:= 2, St.test_units =:= 1, St.cut =:= 0, St.both =:= 0,
    St.train =:= 6, St.test =:= 6,
    terms(F, Orig), terms(Train, TrTs), terms(Test, TeTs),
    subsequence_of_variants(TrTs, Orig),
    subsequence_of_variants(TeTs, Orig),
    length(Orig, N), length(TrTs, NTr), length(TeTs, NTe),
    NTr =:= N - 6, NTe =:= N - 6,
    %   the ground clause of a predicate that rules define is background
    memberchk(pick([], none), TrTs), memberchk(pick([], none), TeTs),
    learn_data_load([Train], [targets(false)], D),
    once(D:'$ddcl_file'(_, dreaml)),
    once(learn_data_pred(D, gender, 1, rv(discrete([m, f])))),
    learn_data_free(D),
    cleanup([F, Train, Test]).

:- end_tests(ddc_learn_split_items).

%   episodes(+N, -Lines): N independent episodes of two objects each,
%   time-indexed facts, a Boolean target given by examples/2 and a
%   background DC clause.
episodes(N, Lines) :-
    Bias = [ 'type(distance(obj, obj):t).', 'type(category(obj)).', 'type(pair(obj, obj)).',
             'type(near(obj, obj):t).', 'type(occluder(obj, obj):t+1).',
             'rv(distance(_, _):t, continuous).', 'rv(category(_), discrete([ball, box])).',
             'rv(occluder(_, _):t+1, boolean).',
             'learn(occluder(A, O):t+1).', 'examples(occluder(A, O):t+1, pair(A, O)).',
             'mode(occluder(_, _):t+1, distance(+, +):t).',
             'mode(occluder(_, _):t+1, category(+)).',
             'near(A, O):t := distance(A, O):t ~= D, D < 0.1.' ],
    findall(L, ( between(1, N, E), episode(E, L) ), Facts),
    append(Bias, Facts, Lines).

episode(E, L) :-
    D is (E mod 7)/20,
    ( E mod 3 =:= 0 -> C = ball ; C = box ),
    (   format(atom(L), 'pair(o1_e~w, o2_e~w).', [E, E])
    ;   format(atom(L), 'distance(o1_e~w, o2_e~w):t ~~= ~w.', [E, E, D])
    ;   format(atom(L), 'category(o2_e~w) ~~= ~w.', [E, C])
    ;   E mod 2 =:= 0, format(atom(L), 'occluder(o1_e~w, o2_e~w):t+1.', [E, E])
    ;   E mod 4 =:= 0, format(atom(L), 'pos(o1_e~w):t ~~= ~w.', [E, D])
    ).

episode_of(T, E) :-
    sub_term(A, T), atom(A), sub_atom(A, B, _, 0, EA), sub_atom(A, _, 2, _, '_e'),
    sub_atom(A, B0, 2, _, '_e'), B is B0+2, atom_number(EA, E), !.

test_episodes(File, Es) :-
    terms(File, Ts),
    findall(E, ( member(T, Ts), episode_of(T, E) ), Es0),
    sort(Es0, Es).

:- begin_tests(ddc_learn_split_units).

test(independent_episodes_split_whole) :-
    episodes(30, Ls),
    split(Ls, [seed(3)], Train, Test, St),
    St.units =:= 30, St.cut =:= 0, St.both =:= 0,
    St.test_units >= 1,
    test_episodes(Train, ETr), test_episodes(Test, ETe),
    length(ETe, K), K =:= St.test_units,
    ord_union(ETr, ETe, All), numlist(1, 30, All),
    ord_intersection(ETr, ETe, []),
    Total is St.train + St.test,
    St.test >= 0.2*Total,
    St.test - 5 < 0.2*Total,                  % an episode has at most 5 facts
    learn_data_load([Train], [], D), learn_data_free(D),
    learn_data_load([Test], [targets(false)], D2), learn_data_free(D2),
    cleanup([Train, Test]).

test(same_seed_same_split_other_seed_other_split) :-
    episodes(30, Ls),
    data(Ls, F),
    outputs(Tr1, Te1), outputs(Tr2, Te2), outputs(Tr3, Te3),
    learn_split_files([F], [train(Tr1), test(Te1), seed(7)], S1),
    learn_split_files([F], [train(Tr2), test(Te2), seed(7)], S2),
    learn_split_files([F], [train(Tr3), test(Te3), seed(8)], _),
    dict_pairs(S1, _, P1), dict_pairs(S2, _, P2), P1 == P2,
    test_episodes(Te1, E1), test_episodes(Te2, E2), test_episodes(Te3, E3),
    E1 == E2, E1 \== E3,
    cleanup([F, Tr1, Te1, Tr2, Te2, Tr3, Te3]).

units_data([ 'type(lives(p, d)).', 'type(works(p, d)).', 'type(owns(p, h)).',
             'type(district(d)).',
             'district(d1).', 'district(d2).', 'district(d3).',
             'lives(p1, d1).', 'works(p1, d2).', 'lives(p2, d2).', 'lives(p3, d3).',
             'owns(p3, h3).', 'owns(p1, h1).', 'owns(p2, h1).',
             'friend(q1, q2).' ]).

test(constants_follow_their_nearest_unit) :-
    units_data(Ls),
    data(Ls, F),
    forall(between(0, 5, Seed),
           ( outputs(Train, Test),
             learn_split_files([F], [train(Train), test(Test), seed(Seed), fraction(0.3),
                                     unit(d)], St),
             %   d1, d2, d3 and the component without a district
             St.units =:= 4,
             terms(Train, TrTs), terms(Test, TeTs),
             forall(member(Ts, [TrTs, TeTs]),
                    (   memberchk(lives(p1, d1), Ts)
                    ->  memberchk(owns(p1, h1), Ts), memberchk(district(d1), Ts)
                    ;   \+ memberchk(owns(p1, h1), Ts)
                    )),
             %   p1 (equally near d1 and d2) and h1 (equally near p1 and
             %   p2) went to d1, whose fact comes first; d2 stays a unit
             (   memberchk(district(d1), TrTs), memberchk(district(d2), TrTs)
             ->  St.cut =:= 0, memberchk(works(p1, d2), TrTs), memberchk(owns(p2, h1), TrTs)
             ;   memberchk(district(d1), TeTs), memberchk(district(d2), TeTs)
             ->  St.cut =:= 0, memberchk(works(p1, d2), TeTs), memberchk(owns(p2, h1), TeTs)
             ;   St.cut =:= 2,
                 \+ memberchk(works(p1, d2), TrTs), \+ memberchk(works(p1, d2), TeTs)
             ),
             cleanup([Train, Test]) )),
    cleanup([F]).

test(connected_worlds_without_a_unit) :-
    units_data(Ls),
    split(Ls, [], Train, Test, St),
    St.units =:= 3,                           % {d1, d2, p1, p2, h1}, {d3, p3, h3}, {q1, q2}
    cleanup([Train, Test]).

:- end_tests(ddc_learn_split_units).

:- begin_tests(ddc_learn_split_errors).

test(one_connected_world_suggests_a_unit_type) :-
    data(['type(link(n, n)).', 'link(a, b).', 'link(b, c).'], F),
    outputs(Train, Test),
    split_error(learn_split_files([F], [train(Train), test(Test)], _), Cause, Where),
    Cause == one_world([n]), Where == F:2,
    message_string(error(ddc_learn(Cause, Where), _), S),
    format(string(Prefix), "~w:2: the facts form one connected world", [F]),
    sub_string(S, 0, _, _, Prefix),
    contains(S, "unit(Type)"), contains(S, "one of: n"),
    \+ exists_file(Train), \+ exists_file(Test),
    cleanup([F]).

test(unknown_unit_type_lists_the_types) :-
    data(['type(link(n, m)).', 'link(a, b).', 'link(c, d).'], F),
    outputs(Train, Test),
    split_error(learn_split_files([F], [train(Train), test(Test), unit(zz)], _), Cause, Where),
    Cause == unknown_unit_type(zz, [m, n]), Where = F:_,
    message_string(error(ddc_learn(Cause, Where), _), S),
    contains(S, "unknown unit type zz: the data's argument types are m, n"),
    cleanup([F]).

test(one_constant_of_the_unit_type) :-
    data(['type(link(n, m)).', 'link(a, b).', 'link(a, c).'], F),
    outputs(Train, Test),
    split_error(learn_split_files([F], [train(Train), test(Test), unit(n)], _), Cause, _),
    Cause == one_unit(n, a),
    cleanup([F]).

test(bad_fraction, [error(domain_error(open_interval(0, 1), 1.5))]) :-
    outputs(Train, Test),
    learn_split_files(['x.pl'], [train(Train), test(Test), fraction(1.5)], _).

test(zero_fraction, [error(domain_error(open_interval(0, 1), 0))]) :-
    outputs(Train, Test),
    learn_split_files(['x.pl'], [train(Train), test(Test), fraction(0)], _).

test(fraction_not_a_number, [error(type_error(number, half))]) :-
    outputs(Train, Test),
    learn_split_files(['x.pl'], [train(Train), test(Test), fraction(half)], _).

test(missing_output_option) :-
    outputs(_, Test),
    split_error(learn_split_files(['x.pl'], [test(Test)], _), Cause, _),
    Cause == missing_option(train).

test(output_that_is_an_input) :-
    data(['link(a, b).', 'link(c, d).'], F),
    outputs(_, Test),
    split_error(learn_split_files([F], [train(F), test(Test)], _), Cause, Where),
    Cause == output_is_input, Where == F:0,
    read_file_to_string(F, S, []), sub_string(S, 0, _, _, "link(a, b)."),
    cleanup([F]).

test(files_of_both_dialects) :-
    dreaml_items(DLs), data(DLs, FD),
    data(['link(a, b).', 'link(c, d).'], FO),
    outputs(Train, Test),
    split_error(learn_split_files([FD, FO], [train(Train), test(Test)], _), Cause, _),
    Cause = mixed_dialects(FD, dreaml, FO, own),
    cleanup([FD, FO]).

test(a_failed_split_leaves_the_outputs_as_they_were) :-
    data(['type(link(n, n)).', 'link(a, b).', 'link(b, c).'], F),
    outputs(Train, Test),
    setup_call_cleanup(open(Train, write, S), format(S, "old.~n", []), close(S)),
    split_error(learn_split_files([F], [train(Train), test(Test)], _), one_world(_), _),
    read_file_to_string(Train, Old, []), Old == "old.\n",
    \+ exists_file(Test),
    file_directory_name(Train, Dir), directory_files(Dir, Es),
    \+ ( member(E, Es), sub_atom(E, _, _, 0, '.tmp'), sub_atom(E, _, _, _, split_t) ),
    cleanup([F, Train]).

:- end_tests(ddc_learn_split_errors).

/*  plunit tests of the structure learner's Prolog side (prolog/ddc/learn.pl,
    prolog/ddc/learn/ddc_learn_data.pl and the modules they re-export,
    prolog/ddc_learn_*.pl) and of the statistical models of learned clauses
    (prolog/ddc/lang/ddc_models.pl).
*/
:- use_module('../../../prolog/ddc').
:- use_module('../../../prolog/ddc/learn').
:- use_module('../../../prolog/ddc/learn/ddc_learn_data').
:- use_module(library(plunit)).
:- use_module(library(lists)).
:- use_module(library(apply)).

%   data(+Lines, -File): learning data in a temporary file.
data(Lines, File) :-
    tmp_file_stream(text, File, S),
    forall(member(L, Lines), format(S, "~w~n", [L])),
    close(S).

load(Lines, M) :-
    data(Lines, F),
    learn_load([F], [], M).

%   load_error(+Lines, -Cause, -Line): loading throws ddc_learn(Cause, _:Line), or the
%   reader's error (lang/ddc_source.pl: a file that cannot be read, Cause its ISO formal
%   term).
load_error(Lines, Cause, Line) :-
    data(Lines, F),
    catch(( learn_load([F], [], M), learn_free(M), Cause = none, Line = 0 ),
          error(Formal, Ctx), true),
    (   var(Formal) -> true
    ;   Formal = ddc_learn(Cause, Where) -> true
    ;   Ctx = context(ddc_source:_, Where) -> Cause = Formal
    ;   throw(error(Formal, Ctx))
    ),
    (   nonvar(Where), Where = _:Line0 -> Line = Line0 ; true ).

close_to(X, Y, Tol) :-
    (   abs(X - Y) =< Tol -> true
    ;   format(user_error, "~w is not within ~w of ~w~n", [X, Tol, Y]), fail
    ).

occlusion_bias([ 'type(distance(obj, obj):t).', 'type(occluder(obj, obj):t+1).',
                 'type(observed(obj):t+1).', 'type(category(obj)).',
                 'rv(distance(_, _):t, continuous).',
                 'rv(category(_), discrete([ball, box])).',
                 'rv(occluder(_, _):t+1, boolean).',
                 'learn(occluder(Occluded, Occluder):t+1).',
                 'examples(occluder(A, O):t+1, pair(A, O)).',
                 'mode(occluder(_, _):t+1, distance(+, +):t).',
                 'mode(occluder(_, _):t+1, observed(+):t+1).',
                 'mode(occluder(_, _):t+1, category(+)).' ]).

occlusion_facts([ 'pair(a1, o1).', 'pair(a2, o2).', 'pair(a3, o3).',
                  'distance(a1, o1):t ~= 0.05.', 'distance(a2, o2):t ~= 0.30.',
                  'category(o1) ~= box.', 'category(o2) ~= ball.',
                  'observed(a2):t+1.',
                  'occluder(a1, o1):t+1.',
                  '0.7 :: occluder(a3, o3):t+1.' ]).

occlusion(M) :-
    occlusion_bias(B), occlusion_facts(F), append(B, F, Ls),
    load(Ls, M).

candidate(M, Node, Kind, Label, C) :-
    learn_candidates(M, Node, Cs),
    member(C, Cs), get_dict(kind, C, Kind), get_dict(labels, C, [Label|_]).

:- begin_tests(ddc_learn_data).

test(time_indexed_facts_become_static_predicates) :-
    occlusion(M),
    learn_data_pred(M, distance_t, 2, rv(continuous)),
    learn_data_pred(M, occluder_t1, 2, rv(discrete([true, false]))),
    learn_data_pred(M, observed_t1, 1, atom),
    M:distance_t(a1, o1, D), D =:= 0.05,
    dc_term(M, occluder_t1(a, b), T), T == occluder(a, b):(t+1),
    learn_free(M).

test(targets_are_described) :-
    occlusion(M),
    learn_targets(M, [T]),
    get_dict(name, T, "occluder(Occluded, Occluder):t+1"),
    get_dict(kind, T, discrete), get_dict(domain, T, [true, false]),
    learn_free(M).

test(value_outside_its_domain_names_the_fact) :-
    load_error(['rv(c(_), discrete([a, b])).', 'type(c(x)).', 'learn(c(X)).', 'c(1) ~= a.',
                'c(2) ~= z.'], Cause, Line),
    Cause = value_not_in_domain(c(2), z, [a, b], _), Line =:= 5.

test(number_for_a_discrete_attribute) :-
    load_error(['rv(c(_), discrete([a, b])).', 'learn(c(X)).', 'c(1) ~= 0.5.'], Cause, Line),
    Cause = continuous_declared_discrete(c(1), 0.5, _), Line =:= 3.

test(non_number_for_a_continuous_attribute) :-
    load_error(['rv(c(_), continuous).', 'learn(c(X)).', 'c(1) ~= high.'], Cause, Line),
    Cause = not_a_number(c(1), high), Line =:= 3.

test(key_with_two_values) :-
    load_error(['learn(c(X)).', 'c(1) ~= a.', 'c(1) ~= b.'], Cause, Line),
    Cause = key_defined_twice(c(1), a, b), Line =:= 3.

test(repeated_fact_is_read_once_with_a_warning, [nondet]) :-
    load(['learn(c(X)).', 'c(1) ~= a.', 'c(1) ~= a.', 'c(2) ~= b.'], M),
    findall(V, M:c(1, V), [a]),
    learn_data_warnings(M, [W]),
    sub_string(W, _, _, _, ":3: c/1: 1 facts repeat"),
    learn_free(M).

test(mode_naming_an_unknown_predicate) :-
    load_error(['learn(c(X)).', 'type(c(e)).', 'mode(c(_), nosuch(+)).', 'c(1) ~= a.'],
               Cause, Line),
    Cause = unknown_mode_predicate(nosuch/1), Line =:= 3.

test(target_without_facts) :-
    load_error(['rv(c(_), discrete([a, b])).', 'learn(c(X)).', 'd(1) ~= a.'], Cause, Line),
    Cause = target_without_facts(c/1), Line =:= 2.

test(rank_listing_a_predicate_twice_is_cyclic) :-
    load_error(['learn(c(X)).', 'c(1) ~= a.', 'rank([c, d, c]).'], Cause, Line),
    Cause = cyclic_rank(c), Line =:= 3.

test(targets_reading_each_other_are_cyclic) :-
    load_error(['type(c(e)).', 'type(d(e)).', 'learn(c(X)).', 'learn(d(X)).',
                'mode(c(_), d(+)).', 'mode(d(_), c(+)).', 'c(1) ~= a.', 'd(1) ~= b.'],
               Cause, Line),
    Cause = cyclic_targets(_), Line =:= 3.

test(rank_breaks_the_cycle) :-
    load(['type(c(e)).', 'type(d(e)).', 'learn(c(X)).', 'learn(d(X)).',
          'mode(c(_), d(+)).', 'mode(d(_), c(+)).', 'rank([d, c]).', 'c(1) ~= a.', 'd(1) ~= b.'],
         M),
    learn_free(M).

test(only_t_and_t_plus_1) :-
    load_error(['learn(c(X)).', 'c(1):t-1 ~= a.'], Cause, Line),
    Cause = unsupported_time(_), Line =:= 2.

test(syntax_error_names_its_line) :-
    load_error(['learn(c(X)).', 'c(1) ~= a.', 'c(2) ~= .'], Cause, Line),
    Cause = syntax_error(_), Line =:= 3.

test(include_of_no_file_names_its_line) :-
    load_error(['learn(c(X)).', ':- include(nowhere).', 'c(1) ~= a.'], Cause, Line),
    Cause = existence_error(source_sink, nowhere), Line =:= 2.

test(included_facts_are_the_datas) :-
    data(['c(2) ~= b.'], Inc),
    format(atom(Include), ':- include(~q).', [Inc]),
    load(['learn(c(X)).', Include, 'c(1) ~= a.'], M),
    learn_data_pred(M, c, 1, rv(discrete([a, b]))),
    learn_free(M).

test(unknown_directive) :-
    load_error(['learn(c(X)).', ':- frobnicate.', 'c(1) ~= a.'], Cause, Line),
    Cause = bad_directive(frobnicate), Line =:= 2.

test(error_is_printed_with_file_and_line) :-
    data(['rv(c(_), continuous).', 'learn(c(X)).', 'c(1) ~= high.'], F),
    catch(learn_load([F], [], _), E, true),
    message_to_codes_(E, S),
    atomic_list_concat([F, ':3: c(1) ~= high: not a number'], Expected),
    sub_atom(S, 0, _, _, Expected).

message_to_codes_(E, S) :-
    E = error(Formal, _),
    message_text(error(Formal, _), S0), atom_string(S, S0).

test(dreaml_dialect_reads_values_last) :-
    load([ 'base(person(p)).', 'base(age(p, a)).', 'base(knows(p, p, x)).',
           'randomVariableNames([age, knows]).', 'thres(age, 2, continuous, []).',
           'thres(knows, 3, continuous, []).', 'learn(age, 2, 2, continuous).',
           'mode(age, avg, (knows(+, -, true), age(+, -))).',
           'person(p1). person(p2).', 'age(p1, 30). age(p2, 40).', 'knows(p1, p2, true).' ], M),
    learn_data_pred(M, knows, 2, rv(discrete([true, false]))),
    learn_data_pred(M, age, 1, rv(continuous)),
    learn_free(M).

:- end_tests(ddc_learn_data).

:- begin_tests(ddc_learn_groundings).

test(examples_are_closed_world_and_uncertain_facts_split_worlds) :-
    occlusion(M),
    learn_root(M, occluder_t1, [], R),
    get_dict(y, R, Ys), get_dict(weight, R, Ws), get_dict(example, R, Es),
    %  a1 true (index 0), a2 false (no fact), a3 true 0.7 / false 0.3
    Ys == [0, 1, 0, 1], Es == [0, 1, 2, 2],
    Ws = [W1, W2, W3, W4], W1 =:= 1, W2 =:= 1, close_to(W3, 0.7, 1e-12), close_to(W4, 0.3, 1e-12),
    learn_free(M).

test(candidate_kinds_and_labels, [nondet]) :-
    occlusion(M),
    learn_root(M, occluder_t1, [], R), get_dict(node, R, N),
    candidate(M, N, numeric, "distance(Occluded, Occluder):t ~= Distance", _),
    candidate(M, N, test, "observed(Occluded):t+1", _),
    candidate(M, N, discrete, "category(Occluder) ~= ball", C),
    get_dict(labels, C, Labels),
    Labels == ["category(Occluder) ~= ball", "category(Occluder) ~= box",
               "\\+ category(Occluder) ~= _"],
    learn_free(M).

test(outcomes_per_row, [nondet]) :-
    occlusion(M),
    learn_root(M, occluder_t1, [], R), get_dict(node, R, N),
    candidate(M, N, numeric, _, C), get_dict(id, C, Id),
    learn_evaluate(M, N, [Id], [O]),
    get_dict(branch, O, Bs), Bs == [0, 0, 1, 1],          % a3 has no distance
    get_dict(x, O, [X1, X2, X3, _]), X1 =:= 0.05, X2 =:= 0.30, X3 \== X3 + 0,
    candidate(M, N, discrete, _, CC), get_dict(id, CC, IdC),
    learn_evaluate(M, N, [IdC], [OC]), get_dict(branch, OC, BCs), BCs == [1, 0, 2, 2],
    learn_free(M).

test(split_partitions_the_rows, [nondet]) :-
    occlusion(M),
    learn_root(M, occluder_t1, [], R), get_dict(node, R, N),
    candidate(M, N, test, _, C), get_dict(id, C, Id),
    learn_split(M, N, Id, [Yes, No]),
    get_dict(row, Yes, [1]), get_dict(row, No, [0, 2, 3]),
    learn_free(M).

test(uncertain_feature_splits_a_row_into_weighted_worlds) :-
    load([ 'type(y(e)).', 'type(f(e)).', 'learn(y(X)).', 'mode(y(_), f(+)).',
           'y(1) ~= a.', 'y(2) ~= b.', '0.25 :: f(1).' ], M),
    learn_root(M, y, [], R), get_dict(node, R, N),
    learn_candidates(M, N, [C]), get_dict(id, C, Id),
    learn_evaluate(M, N, [Id], [O]),
    get_dict(row, O, Rows), get_dict(branch, O, Bs), get_dict(factor, O, Fs), get_dict(pure, O, Ps),
    Rows == [0, 0, 1], Bs == [0, 1, 1], Ps == [false, false, true],
    Fs = [F1, F2, F3], close_to(F1, 0.25, 1e-12), close_to(F2, 0.75, 1e-12), F3 =:= 1,
    learn_free(M).

test(new_variables_bind_to_the_first_solution, [nondet]) :-
    load([ 'type(y(e)).', 'type(link(e, e)).', 'type(v(e)).', 'rv(v(_), continuous).',
           'learn(y(X)).', 'mode(y(_), link(+, -)).', 'mode(y(_), v(+)).',
           'y(1) ~= a.', 'y(2) ~= b.', 'v(11) ~= 0.7.', 'link(1, 10).', 'link(1, 11).',
           'v(10) ~= 0.5.' ], M),
    learn_root(M, y, [], R), get_dict(node, R, N),
    candidate(M, N, test, "(link(X, E) -> true)", C), get_dict(id, C, Id),
    get_dict(fresh, C, true),
    learn_split(M, N, Id, [Yes, _]),
    get_dict(node, Yes, YN), get_dict(row, Yes, [0]),
    candidate(M, YN, numeric, Label, CV), get_dict(id, CV, IdV),
    Label == "v(E) ~= V",
    learn_evaluate(M, YN, [IdV], [O]), get_dict(x, O, [X]), X =:= 0.5,
    learn_free(M).

test(count_and_mean_over_neighbours, [nondet]) :-
    load([ 'type(y(e)).', 'type(link(e, e)).', 'type(v(e)).', 'rv(v(_), continuous).',
           'learn(y(X)).', 'mode(y(_), count, link(+, -)).', 'mode(y(_), mean, (link(+, -), v(+))).',
           'y(1) ~= a.', 'y(2) ~= b.', 'link(1, 10).', 'link(1, 11).', 'v(10) ~= 0.5.',
           'v(11) ~= 0.7.' ], M),
    learn_root(M, y, [], R), get_dict(node, R, N),
    candidate(M, N, count, _, C), get_dict(id, C, Id),
    learn_evaluate(M, N, [Id], [O]), get_dict(x, O, Xs), Xs == [2, 0],
    candidate(M, N, agg_numeric, L, CM), get_dict(id, CM, IdM),
    L == "(findall_forward(V, (link(X, E), v(E) ~= V), L), mean_list(L, MeanV))",
    learn_evaluate(M, N, [IdM], [OM]),
    get_dict(x, OM, [Mean, _]), close_to(Mean, 0.6, 1e-12), get_dict(branch, OM, [0, 1]),
    learn_free(M).

test(weights_of_groundings) :-
    load([ 'learn(y(X)).', 'y(1) ~= a.', 'y(2) ~= b.', 'weight(y(2), 3).' ], M),
    example_weight(M, y(1), W1), example_weight(M, y(2), W2),
    learn_root(M, y, [], R), get_dict(weight, R, Ws),
    learn_free(M),
    W1 =:= 1, W2 =:= 3, Ws == [1.0, 3].

test(a_grounding_weighted_twice) :-
    load_error([ 'learn(y(X)).', 'y(1) ~= a.', 'weight(y(1), 3).', 'weight(y(1), 2).' ],
               Cause, Line),
    Cause == weighted_twice(y(1), 3, 2), Line =:= 4.

test(mode_and_antimode_over_neighbours_take_their_values_branch, [nondet]) :-
    load([ 'type(y(e)).', 'type(link(e, e)).', 'type(c(e)).', 'rv(c(_), discrete([r, g])).',
           'learn(y(X)).', 'mode(y(_), mode, (link(+, -), c(+))).',
           'mode(y(_), antimode, (link(+, -), c(+))).',
           'y(1) ~= a.', 'y(2) ~= b.', 'y(3) ~= a.', 'link(1, 10).', 'link(1, 11).',
           'link(1, 12).', 'link(3, 12).', 'c(10) ~= g.', 'c(11) ~= g.', 'c(12) ~= r.' ], M),
    learn_root(M, y, [], R), get_dict(node, R, N),
    learn_candidates(M, N, Cs),
    findall(Id, ( member(C, Cs), get_dict(kind, C, agg_discrete), get_dict(id, C, Id) ), [IdMo, IdAnti]),
    %  branches: one per value of the domain [r, g], then the empty list
    learn_evaluate(M, N, [IdMo, IdAnti], [OMo, OAnti]),
    get_dict(branch, OMo, [1, 2, 0]), get_dict(branch, OAnti, [0, 2, 0]),
    learn_free(M).

:- end_tests(ddc_learn_groundings).

:- begin_tests(ddc_learn_clauses).

test(logistic_clause_in_the_papers_order, [nondet]) :-
    occlusion(M),
    learn_root(M, occluder_t1, [], R), get_dict(node, R, N),
    candidate(M, N, numeric, _, C), get_dict(id, C, Id),
    learn_split(M, N, Id, [Def, _]), get_dict(node, Def, DN),
    learn_leaf_text(M, DN, "logistic([-16.9, 0.8])", [0], T),
    get_dict(clause, T, Text),
    %  the examples' goal first (the head's variables bound, for forward reasoning)
    Text == "occluder(Occluded, Occluder):t+1 ~ finite([P1:true, P2:false]) :=\n    pair(Occluded, Occluder),\n    distance(Occluded, Occluder):t ~= Distance,\n    logistic([Distance], [-16.9, 0.8], P1),\n    P2 is 1-P1.",
    learn_free(M).

test(learned_clause_text_loads_in_the_engine_and_gives_the_model, [nondet]) :-
    occlusion(M),
    learn_root(M, occluder_t1, [], R), get_dict(node, R, N),
    candidate(M, N, numeric, _, C), get_dict(id, C, Id),
    learn_split(M, N, Id, [Def, Undef]), get_dict(node, Def, DN), get_dict(node, Undef, UN),
    learn_leaf_text(M, DN, "logistic([-16.9, 0.8])", [0], T1), get_dict(clause, T1, C1),
    learn_leaf_text(M, UN, "finite([0.25, 0.75])", [], T2), get_dict(clause, T2, C2),
    data(['distance(a, b):t ~ val(0.1).', 'pair(a, b) := true.', C1, C2], F),
    ddc_load(F, P),
    query((occluder(a, b):t+1) ~= true, Prob, [samples(10), program(P), time(0)]),
    Expected is 1/(1+exp(16.9*0.1 - 0.8)),
    close_to(Prob, Expected, 1e-9),
    learn_free(M).

test(a_program_scored_on_data) :-
    occlusion(M),
    data([ 'occluder(A, O):t+1 ~ finite([0.9:true, 0.1:false]) := category(O) ~= box.',
           'occluder(A, O):t+1 ~ finite([0.2:true, 0.8:false]) := \\+ category(O) ~= box.' ],
         P),
    learn_program_scores(M, P, [occluder_t1], [], [S]),
    get_dict(n, S, 3), get_dict(uncovered, S, 0),
    %  a1 box true, a2 ball false, a3 no category: 0.7 true + 0.3 false
    LL is log(0.9) + log(0.8) + 0.7*log(0.2) + 0.3*log(0.8),
    get_dict(log_likelihood, S, L), close_to(L, LL, 1e-9),
    get_dict(accuracy, S, A), close_to(A, (1 + 1 + 0.3)/3, 1e-9),
    learn_free(M).

test(a_test_value_the_program_does_not_know) :-
    load(['learn(c(X)).', 'c(1) ~= a.', 'c(2) ~= z.'], M),
    data(['c(X) ~ finite([0.5:a, 0.5:b]).'], P),
    catch(learn_program_scores(M, P, [c], [], _), error(ddc_learn(Cause, _:Line), _), true),
    Cause = value_not_in_program(c(2), z, [a, b]), Line =:= 3,
    learn_free(M).

:- end_tests(ddc_learn_clauses).

:- begin_tests(ddc_learn_modules).

%   The entry modules that Python (bridge/learning.py) and the tests load
%   keep their API while the code lives in modules of one job each.
test(learner_api, Exports == [ learn_background/3, learn_background_for/3, learn_candidates/3,
                              learn_check/1, learn_clause/5, learn_clause_text/3,
                              learn_evaluate/4, learn_evaluate_rows/5, learn_forget/2,
                              learn_forget_rows/2, learn_free/1, learn_groundings/3,
                              learn_leaf_text/5, learn_load/3, learn_program_scores/5,
                              learn_root/4, learn_root_model/3, learn_split/4, learn_subset/4,
                              learn_targets/2, learn_tree_text/3 ]) :-
    module_property(ddc_learn, exports(E)), msort(E, Exports).

test(data_api, Exports == [ data_read_terms/3, dc_goal/4, dc_term/3, dist_points/3,
                           example_weight/3, fact_where/3, internal_key/3, learn_data_free/1,
                           learn_data_load/3, learn_data_pred/4, learn_data_record/4,
                           learn_data_targets/2, learn_data_warnings/2, message_text/2,
                           pick/3 ]) :-
    module_property(ddc_learn_data, exports(E)), msort(E, Exports).

test(data_operators) :-
    module_property(ddc_learn_data, exported_operators(Ops)),
    forall(member(Op, [op(700, xfx, ~), op(700, xfx, ~=), op(1105, xfx, :=),
                       op(1105, xfx, <-), op(1150, xfx, pr), op(700, xfx, ::)]),
           memberchk(Op, Ops)).

%   The learner's records are read by name and compiled to arg/3.
test(record_accessors_inline) :-
    clause(ddc_learn_candidates:branch_count(_, _), Body),
    Body = (arg(2, _, _), _).

:- end_tests(ddc_learn_modules).

:- begin_tests(ddc_models).

test(logistic_of_the_paper) :-
    logistic([0.05], [-16.9, 0.8], P),
    close_to(P, 1/(1+exp(16.9*0.05 - 0.8)), 1e-12).

test(softmax_first_row_is_the_reference) :-
    softmax([2.0], [[0, 0], [1.0, -1.0], [0.5, 0.0]], Ps),
    Zs = [0.0, 1.0, 1.0],
    sum_list(Ps, S), close_to(S, 1.0, 1e-12),
    maplist([Z, P]>>( close_to(P, exp(Z)/(1 + 2*exp(1.0)), 1e-12) ), Zs, Ps).

test(softmax_needs_one_more_weight_than_inputs, [error(domain_error(weights_one_more_than_inputs(1), _))]) :-
    softmax([1.0], [[1.0]], _).

test(mean_of_no_values_is_undefined, [fail]) :-
    mean_list([], _).

test(mean_list) :-
    mean_list([1, 2, 6], M), M =:= 3.

test(mode_breaks_ties_by_the_standard_order) :-
    mode_list([b, a, b, a, c], M), M == a,
    mode_list([c, c, a], M2), M2 == c,
    antimode_list([c, c, a, b, b], L), L == a,
    \+ mode_list([], _).

test(models_in_a_static_query) :-
    data([ 'x ~ val(2.0).',
           'c ~ finite([P1:r, P2:g, P3:b]) := x ~= X, softmax([X], [[0, 0], [1.0, -1.0], [0.5, 0.0]], [P1, P2, P3]).',
           'm ~ val(M) := findall(V, member(V, [1, 2, 6]), L), mean_list(L, M).' ], F),
    ddc_load(F, P),
    query(c ~= r, Pr, [samples(10), program(P)]),
    close_to(Pr, 1/(1 + 2*exp(1.0)), 1e-9),
    query(m ~= 3, Pm, [samples(10), program(P)]), Pm =:= 1.

test(models_in_both_filter_engines) :-
    data([ 'x:t+1 ~ val(2.0) := true.',
           'c:t+1 ~ finite([P1:r, P2:g, P3:b]) := x:t+1 ~= X, softmax([X], [[0, 0], [1.0, -1.0], [0.5, 0.0]], [P1, P2, P3]).',
           'm:t+1 ~ val(M) := x:t+1 ~= X, mean_list([X, 4.0], M).' ], F),
    forall(member(E, [batched, per_particle]),
           ( filter_new(F, 400, 1, [engine(E), threads(1)], Fl),
             filter_engine(Fl, E),
             filter_step(Fl, [], [], _),
             filter_holds(Fl, c:t ~= r, Flags),
             sum_list(Flags, NT),
             P is NT / 400, Expected is 1/(1 + 2*exp(1.0)),
             SE is sqrt(Expected*(1-Expected)/400),
             close_to(P, Expected, 5*SE),
             filter_values(Fl, M, m:t ~= M, Ms),
             forall(member(V, Ms), V =:= 3.0),
             filter_free(Fl) )).

:- end_tests(ddc_models).

/*  plunit tests of prolog/ddc/filter/ddc_bridge.pl: the predicates bridge.Filter calls
    through janus, here called directly on the wumpus example (25 cells, one
    agent; prolog/examples/filter/wumpus.pl).
*/
:- use_module('../../../prolog/ddc').
:- use_module('../../../prolog/ddc/filter/ddc_bridge').
:- use_module('../../../prolog/ddc/filter/ddc_belief', [read_frame_file/2]).
:- use_module('../../../prolog/ddc/filter/ddc_weights').
:- use_module(library(plunit)).
:- use_module(library(lists)).
:- use_module(library(apply)).

wumpus(Path) :-
    module_property(ddc_bridge, file(F)),
    file_directory_name(F, Dir),
    atomic_list_concat([Dir, '/../../examples/filter/wumpus.pl'], Path).

%   new_filter(+N, -Key): a wumpus filter of N particles (seed 3, one thread).
new_filter(N, Key) :-
    wumpus(W),
    bridge_new(W, N, 3, true, 1, per_particle, Key, Used),
    assertion(Used == per_particle).

%   step_null(+Key, -LW): a step of wall up, free right, no action; LW the step's normalised
%   log weights (threshold 0: never resampled).
step_null(Key, LW) :-
    bridge_weighted_step(Key, ["observation(up) ~= wall", "observation(right) ~= free"],
                         ["action(null)"], [], 0.0, systematic, [0.5], LW, _, _, _, _, none).

%   bad_step(+Key, +ObsTexts, +ActTexts, -Error): the error a step with these texts raises.
bad_step(Key, ObsTexts, ActTexts, E) :-
    catch(bridge_weighted_step(Key, ObsTexts, ActTexts, [], 0.0, systematic, [0.5],
                               _, _, _, _, _, _),
          E, true),
    assertion(nonvar(E)).

%   printed(+Error, -Text): Error as print_message/2 prints it (without the prefix).
printed(E, S) :-
    '$messages':translate_message(E, Lines, []),
    with_output_to(string(S0), print_message_lines(current_output, '', Lines)),
    split_string(S0, "", "\n ", [S]).

%   message(+Error, -Message): the bridge's one-line message in an input error's context.
message(error(_, context(ddc_bridge:_, M)), M).

:- begin_tests(ddc_bridge).

test(new_makes_a_filter_at_time_0_and_free_ends_it) :-
    new_filter(20, Key),
    assertion(string(Key) ; atom(Key)),
    bridge_time(Key, T),
    assertion(T == 0),
    bridge_free(Key),
    catch(bridge_time(Key, _), E, true),
    assertion(nonvar(E)).

test(new_raises_the_error_of_a_bad_program_naming_its_line) :-
    tmp_file_stream(text, File, Out),
    format(Out, "position:0 ~~ val((0,0)).~nmaze(X, Y):0 ~~ finite([0.6:free 0.4:wall]).~n", []),
    close(Out),
    catch(bridge_new(File, 10, 1, true, 1, auto, _, _), E, true),
    assertion(E = error(syntax_error(_), _)),
    printed(E, Codes),
    assertion(sub_string(Codes, _, _, _, ":2")).

test(step_gives_one_float_log_weight_per_particle_and_advances) :-
    new_filter(30, Key),
    step_null(Key, LW),
    length(LW, 30),
    assertion(maplist(float, LW)),
    % up = wall, right = free: each particle weighs 0.81, 0.09 or 0.01 (0.9 or 0.1 per
    % sensor) before the weights are normalised
    foldl([L, S0, S]>>(S is S0 + exp(L)), LW, 0.0, Sum),
    assertion(abs(Sum - 1) < 1.0e-12),
    max_list(LW, Max),
    forall(member(L, LW),
           assertion(( member(A, [0.81, 0.09, 0.01]), member(B, [0.81, 0.09, 0.01]),
                       abs(exp(L - Max) - A / B) < 1.0e-9 ))),
    bridge_time(Key, 1),
    bridge_free(Key).

test(step_names_the_item_that_does_not_parse_and_keeps_the_particles) :-
    new_filter(10, Key),
    bad_step(Key, ["observation(up) ~= wall", "observation(right ~= free"], [], E),
    assertion(E = error(syntax_error(_), context(ddc_bridge:bridge_weighted_step/13, _))),
    message(E, M),
    assertion(sub_string(M, 0, _, _, "observation 2 (observation(right ~= free)")),
    bad_step(Key, [], ["action(X)"], E2),
    assertion(E2 = error(instantiation_error, _)),
    message(E2, M2),
    assertion(sub_string(M2, 0, _, _, "action 1 (action(X)): not ground")),
    printed(E2, Printed),
    assertion(Printed == M2),
    bridge_time(Key, 0),
    bridge_free(Key).

test(a_long_text_is_cut_in_the_message) :-
    new_filter(10, Key),
    length(Cs, 300), maplist(=(0'a), Cs), string_codes(Long, Cs),
    string_concat(Long, "(", Bad),
    bad_step(Key, [Bad], [], E),
    message(E, M),
    assertion(sub_string(M, _, _, _, "301 characters")),
    bridge_free(Key).

test(undo_returns_to_the_time_before_the_step) :-
    new_filter(10, Key),
    step_null(Key, _),
    bridge_time(Key, 1),
    bridge_undo(Key),
    bridge_time(Key, 0),
    bridge_free(Key).

test(holds_flags_every_particle) :-
    new_filter(40, Key),
    bridge_holds(Key, "position:t ~= (0,0)", Flags),
    assertion((length(Flags, 40), maplist(==(1), Flags))),
    bridge_holds(Key, "maze(0,1):t ~= wall", Walls),
    sum_list(Walls, S),
    assertion((S > 0, S < 40)),
    catch(bridge_holds(Key, "maze(0,1):t ~=", _), E, true),
    assertion(E = error(syntax_error(_), context(ddc_bridge:bridge_holds/3, _))),
    message(E, M),
    assertion(sub_string(M, 0, _, _, "goal maze(0,1):t ~=: ")),
    bridge_free(Key).

test(weighted_step_normalises_and_resamples_below_the_threshold) :-
    new_filter(30, Key),
    Obs = ["observation(up) ~= wall", "observation(right) ~= free"],
    bridge_weighted_step(Key, Obs, ["action(null)"], [], 0.0, residual, [], LW, Inc, ESS, Inf,
                         Drawn, Is),
    assertion(Inf == false),
    assertion(Is == none), assertion(Drawn == 0),
    length(LW, 30),
    foldl([L, S0, S]>>(S is S0 + exp(L)), LW, 0.0, Sum),
    assertion(abs(Sum - 1) < 1.0e-12),
    assertion(ESS > 0), assertion(ESS =< 30.0000001),
    assertion(Inc < 0),
    % (threshold 2: always below) resampled from the given uniforms, the weights uniform
    length(Us, 30), maplist(=(0.5), Us),
    bridge_weighted_step(Key, Obs, ["action(null)"], LW, 2.0, residual, Us, LW2, _, _, _,
                         Drawn2, Is2),
    assertion(LW2 == []),
    length(Is2, 30),
    assertion(between(0, 30, Drawn2)),
    bridge_time(Key, 2),
    bridge_free(Key).

test(weighted_step_undoes_a_frame_of_weight_zero) :-
    new_filter(10, Key),
    % (a value outside `finite`'s support: every particle weight 0)
    bridge_weighted_step(Key, ["observation(up) ~= maybe"], ["action(null)"], [], 0.5,
                         systematic, [0.5], LW, Inc, ESS, _, Drawn, Is),
    assertion(Inc =:= -inf), assertion(ESS == 0.0), assertion(Drawn == 0),
    assertion(Is == none), assertion(LW == []),
    bridge_time(Key, T),
    assertion(T == 0),
    bridge_free(Key).

test(values_map_tuples_lists_compounds_and_no_solution) :-
    new_filter(5, Key),
    bridge_values(Key, "ddc_bridge_pair(P, position:t ~= P)", Ps),
    assertion(Ps == [0-0, 0-0, 0-0, 0-0, 0-0]),
    bridge_values(Key, "ddc_bridge_pair([f(X), \"s\", 1.5, Y], X = a)", Vs),
    assertion(Vs = [["f(a)", "s", 1.5, "_"]|_]),
    catch(bridge_values(Key, "ddc_bridge_pair(X, X = )", _), E, true),
    message(E, M),
    assertion(sub_string(M, 0, _, _, "goal ddc_bridge_pair(X, X = ): ")),
    bridge_values(Key, "ddc_bridge_pair(X, (X = none, fail))", Nones),
    assertion(Nones == [@(none), @(none), @(none), @(none), @(none)]),
    bridge_values(Key, "ddc_bridge_pair(X, X = none)", Atoms),
    assertion(Atoms == [none, none, none, none, none]),
    bridge_free(Key).

test(numeric_rows_flatten_numbers_and_tuples) :-
    new_filter(4, Key),
    bridge_numeric_rows(Key, "ddc_bridge_pair(P, position:t ~= P)", W, Fs, Vs),
    assertion(W == 2),
    assertion(Fs == [0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0]),
    assertion(Vs == []),
    bridge_numeric_rows(Key, "ddc_bridge_pair(V, maze(0,1):t ~= V)", W2, Fs2, Vs2),
    assertion(W2 == 0), assertion(Fs2 == []),
    assertion((length(Vs2, 4), subtract(Vs2, [wall, free], []))),
    catch(bridge_numeric_rows(Key, "ddc_bridge_pair(V, maze(0,1):t ~=", _, _, _), E, true),
    assertion(E = error(syntax_error(_), _)),
    bridge_free(Key).

%   (Rows that cannot be copied into the caller's memory, here none, come as a list.)
test(rows_into_memory_or_as_a_list) :-
    new_filter(4, Key),
    bridge_rows_into(Key, "ddc_bridge_pair(P, position:t ~= P)", 0, 0, W, Fs, Vs),
    assertion(W == 2),
    assertion(Fs == [0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0]),
    assertion(Vs == []),
    bridge_rows_into(Key, "ddc_bridge_pair(V, maze(0,1):t ~= V)", 0, 0, W2, Fs2, _),
    assertion(W2 == 0), assertion(Fs2 == []),
    catch(bridge_rows_into(Key, "ddc_bridge_pair(V, maze(0,1):t ~= V)", x, 0, _, _, _), E, true),
    assertion(E = error(type_error(integer, x), _)),
    bridge_free(Key).

test(rename_swaps_names_in_the_particles_given_and_reports_bad_renamings) :-
    new_filter(4, Key),
    step_null(Key, _),
    Pair = "ddc_bridge_pair(V, maze(0,1):t ~= V)",
    bridge_values(Key, Pair, Vs0),
    bridge_rename(Key, ["wall", "free"], ["free", "wall"], [2, 4]),
    bridge_values(Key, Pair, Vs1),
    forall(nth1(I, Vs0, V0),
           (   nth1(I, Vs1, V1),
               (   I mod 2 =:= 0
               ->  assertion(( member(V0-V1, [wall-free, free-wall]) -> true ))
               ;   assertion(V1 == V0)
               )
           )),
    catch(bridge_rename(Key, ["wall"], ["free"], [1]), E, true),
    assertion(E = error(domain_error(_, _), _)),
    printed(E, M),
    assertion(sub_string(M, _, _, _, "permutation")),
    catch(bridge_rename(Key, ["wall", "free"], ["free", "wall"], [5]), E2, true),
    printed(E2, M2),
    assertion(sub_string(M2, _, _, _, "5")),
    bridge_values(Key, Pair, Vs2),
    assertion(Vs2 == Vs1),
    bridge_free(Key).

test(frames_come_as_texts_that_read_back_as_the_terms_read) :-
    tmp_file_stream(text, Frames, Out),
    format(Out, '~w~n', ['{"observations": ["observation(p) ~= (0.1, -1, 1.0e-300, 12345678901234567890)", "observation(q) ~= \\"s\\"", "seen(\'A b\', [x|y], {z}, - (1), a- -1, (:-), \'=..\')"], "actions": ["action(move(b, (0.1,0,0)))"]}']),
    format(Out, '~w~n', ['{"observations": [{"observation": "pos(b)", "value": [0.30000000000000004, "Ab", [1, 2], false]}]}']),
    close(Out),
    read_frame_file(Frames, Terms),
    bridge_frames(Frames, Texts),
    length(Terms, 2),
    maplist(same_frame, Terms, Texts).

test(a_bad_frame_file_raises_file_line_and_cause) :-
    tmp_file_stream(text, Frames, Out),
    format(Out, '{}~n{"observations": [1]}~n', []),
    close(Out),
    catch(bridge_frames(Frames, _), E, true),
    assertion(E = error(ddc_belief(frame(_, 2, _)), _)),
    printed(E, M),
    atom_concat(Frames, ':2: observations[1]: ', Start),
    assertion(sub_string(M, 0, _, _, Start)).

test(with_includes_gives_the_file_and_the_files_it_includes) :-
    module_property(ddc_bridge, file(F)),
    file_directory_name(F, Dir),
    atomic_list_concat([Dir, '/../../too.pl'], Too),
    bridge_with_includes(Too, [First|Included]),
    assertion(file_base_name(First, 'too.pl')),
    maplist(file_base_name, Included, Names),
    assertion((memberchk('too_base.pl', Names), memberchk('too_motion.pl', Names))).

:- end_tests(ddc_bridge).

same_frame(frame(Line, Obs, Acts), -(Line, ObsTexts, ActTexts)) :-
    maplist(reads_as, ObsTexts, Obs),
    maplist(reads_as, ActTexts, Acts).

reads_as(Text, Term) :-
    term_string(T, Text, [module(ddc)]),
    assertion(T == Term).

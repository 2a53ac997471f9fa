/*  plunit tests of the ISO error terms of the engine's API (prolog/ddc.pl,
    "Errors"): a misuse of the API raises error(Formal, context(PI, Msg))
    with Formal an ISO error term and PI the predicate called.
*/
:- use_module('../../../prolog/ddc').
:- use_module(library(plunit)).

random_walk(File) :-
    source_file(random_walk(_), This),
    file_directory_name(This, Dir),
    atomic_list_concat([Dir, '/../../../prolog/examples/filter/random_walk.pl'], File0),
    absolute_file_name(File0, File).

new_filter(Engine, F) :-
    random_walk(File),
    filter_new(File, 20, 1, [engine(Engine)], F).

:- begin_tests(ddc_api_errors).

test(freed_filter_is_an_existence_error, [forall(member(Engine, [per_particle, batched]))]) :-
    new_filter(Engine, F),
    filter_free(F),
    catch(filter_time(F, _), E, true),
    E = error(existence_error(ddc_filter, G), context(ddc_filter:filter_time/2, _)),
    G == F.

test(a_non_filter_is_an_existence_error,
     [error(existence_error(ddc_filter, no_such_filter), _)]) :-
    filter_size(no_such_filter, _).

test(non_ground_observation_is_an_instantiation_error,
     [forall(member(Engine, [per_particle, batched]))]) :-
    new_filter(Engine, F),
    catch(filter_step(F, [observation(y) ~= _], [], _), E, true),
    filter_free(F),
    E = error(instantiation_error, context(ddc_filter:filter_step/4, Msg)),
    sub_atom(Msg, 0, _, _, 'not ground').

test(a_second_undo_is_a_permission_error, [forall(member(Engine, [per_particle, batched]))]) :-
    new_filter(Engine, F),
    filter_step(F, [observation(y) ~= 0.5], [], _),
    filter_undo(F),
    catch(filter_undo(F), E, true),
    filter_free(F),
    E = error(permission_error(undo, ddc_filter, G), context(ddc_filter:filter_undo/1, _)),
    G == F.

test(bad_resampling_indices_are_a_domain_error,
     [forall(member(Is-Engine, [[0,1]-per_particle, [0,1]-batched]))]) :-
    new_filter(Engine, F),
    catch(filter_resample(F, Is), E, true),
    filter_free(F),
    E = error(domain_error(particle_indices(20), Is), context(ddc_filter:filter_resample/2, _)).

test(indices_of_no_atoms_are_a_type_error, [forall(member(Engine, [per_particle, batched]))]) :-
    new_filter(Engine, F),
    catch(filter_indices(F, X, x:t ~= X, [a, 1.5], _), E, true),
    filter_free(F),
    E = error(type_error(_, _), _).

test(index_out_of_range_is_a_domain_error) :-
    new_filter(per_particle, F),
    numlist(1, 20, Is),                     % 20 is out of range 0..19
    catch(filter_resample(F, Is), E, true),
    filter_free(F),
    E = error(domain_error(particle_indices(20), Is), context(_, Msg)),
    once(sub_atom(Msg, _, _, _, 'out of range')).

test(query_on_a_module_without_program_is_an_existence_error,
     [error(existence_error(ddc_program, no_such_module), _)]) :-
    ddc_query(no_such_module, [], true, [], _, _).

test(expectation_of_a_non_number_is_a_type_error) :-
    tmp_file_stream(text, File, S),
    format(S, "~w~n", ['colour ~ finite([0.5:red, 0.5:blue]).']),
    close(S),
    ddc_load(File, M),
    catch(expectation([], colour ~= X, X, _, [program(M), samples(10)]), E, true),
    E = error(type_error(number, V), context(ddc:expectation/5, _)),
    memberchk(V, [red, blue]).

:- end_tests(ddc_api_errors).

/*  Tests of ddc_records.pl: records with named fields, accessed inline.
*/

:- use_module(library(plunit)).
:- use_module(library(lists)).
:- use_module('../../../prolog/ddc/lang/ddc_records').
:- use_module('../../../prolog/ddc').
:- use_module('../../../prolog/ddc/filter/ddc_belief').
:- use_module('../../../prolog/ddc/learn').
:- use_module('../../../prolog/ddc/learn/ddc_learn_data').

% load_text(+Module, +Text): a module file declaring what Text says,
% written and loaded (again, when the module was loaded from it before).
load_text(Module, Text) :-
    module_property(ddc_records, file(Lib)),
    (   written(Module, File)
    ->  true
    ;   atom_concat('ddc_records_test_', Module, Base),
        tmp_file(Base, File0),
        file_name_extension(File0, pl, File),
        assertz(written(Module, File))
    ),
    setup_call_cleanup(open(File, write, S),
                       format(S, ":- module(~q, []).~n:- use_module(~q).~n~w~n",
                              [Module, Lib, Text]),
                       close(S)),
    load_files(File, [if(true)]).

:- dynamic written/2.

:- begin_tests(ddc_records).

test(accessors_read_and_write_by_name) :-
    load_text(rt_point, ":- record_type point(x, y, z).\n"),
    P = point(1, 2, 3),
    rt_point:point_y(P, Y), assertion(Y == 2),
    rt_point:set_point_x(P, 10), assertion(P == point(10, 2, 3)),
    rt_point:nb_set_point_z(P, 30), assertion(P == point(10, 2, 30)),
    rt_point:point_fields(Fs), assertion(Fs == [x, y, z]),
    rt_point:new_point(N), assertion(( N = point(A, B, C), var(A), var(B), var(C) )).

test(accessors_compile_to_arg) :-
    load_text(rt_inline, ":- record_type pair(left, right).\n\c
                          get_right(P, R) :- pair_right(P, R).\n\c
                          make(L, P) :- make_pair([left(L)], P).\n"),
    clause(rt_inline:get_right(_, _), Body1),
    assertion(Body1 = arg(2, _, _)),
    clause(rt_inline:make(_, P), Body2),
    assertion(\+ sub_term(make_pair(_, _), Body2)),
    assertion(( Body2 == true -> P = pair(_, _) ; Body2 = (_ = pair(_, _)) )).

test(make_sets_the_fields_given) :-
    load_text(rt_make, ":- record_type box(w, h).\n"),
    rt_make:make_box([h(5)], B),
    assertion(( B = box(W, 5), var(W) )).

test(make_with_an_unknown_field, [error(existence_error(record_field, box2:depth), _)]) :-
    load_text(rt_make2, ":- record_type box2(w, h).\n"),
    rt_make2:make_box2([depth(1)], _).

test(two_modules_may_not_declare_the_same_accessors,
     [error(permission_error(declare, record_accessor, _), _)]) :-
    load_text(rt_first, ":- record_type shared_rec(a).\n"),
    ddc_records:record_clauses(shared_rec(a), rt_second, _).

test(the_first_declaration_stays_after_a_clash) :-
    load_text(rt_first2, ":- record_type shared_rec2(a).\n"),
    catch(ddc_records:record_clauses(shared_rec2(a), rt_second2, _), _, true),
    ddc_records:field(shared_rec2_a, get, 1, Declarer),
    assertion(Declarer == rt_first2).

test(a_module_loaded_again_declares_afresh) :-
    load_text(rt_again, ":- record_type again(a, b).\n"),
    load_text(rt_again, ":- record_type again(a, b, c).\n"),
    rt_again:again_c(again(1, 2, 3), C),
    assertion(C == 3).

test(template_must_name_distinct_fields, [error(type_error(record_template, dup(a, a)), _)]) :-
    ddc_records:record_clauses(dup(a, a), rt_dup, _).

% The engine's hot paths read their records through accessors: each one
% must be compiled to the arg/3 (...) instruction, not left as a call.
test(every_accessor_of_the_engine_is_compiled_inline) :-
    findall(M:N/A-Called,
            ( current_module(M),
              module_property(M, file(F)),
              sub_atom(F, _, _, _, '/prolog/ddc'),
              current_predicate(M:N/A),
              functor(H, N, A),
              \+ predicate_property(M:H, imported_from(_)),
              catch(clause(M:H, B), _, fail),
              sub_term(G, B), compound(G), compound_name_arity(G, Called, 2),
              ( ddc_records:field(Called, _, _, _)
              ; ddc_records:constructor(Called, _, _, _)
              ) ),
            Calls),
    assertion(Calls == []).

:- end_tests(ddc_records).

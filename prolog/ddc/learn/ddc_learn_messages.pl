/*  ddc_learn_messages.pl -- the text of the learner's errors and warnings.
*/

:- module(ddc_learn_messages,
          [ message_text/2              % +Message, -Text
          ]).

/** <module> Messages of the structure learner

Errors are error(ddc_learn(Cause, Where), _), warnings
ddc_learn_warning(Where-Cause); both print as `File:Line: cause`.  A
file that cannot be read (no such file, a syntax error) is the reader's
ISO error (lang/ddc_source.pl), printed the same way.
*/

%!  message_text(+Message, -Text:string) is det.
%
%   A message term of this module rendered as print_message/2 would.
message_text(Msg, Text) :-
    (   phrase(prolog:message(Msg), Lines)
    ->  with_output_to(string(Text), print_message_lines(current_output, '', Lines))
    ;   term_string(Msg, Text)
    ).

                 /*******************************
                 *            MESSAGES          *
                 *******************************/

:- multifile prolog:message//1.

prolog:message(error(ddc_learn(Cause, Where), _)) -->
    learn_where(Where),
    learn_cause(Cause).
prolog:message(ddc_learn_warning(Where-Cause)) -->
    learn_where(Where),
    learn_cause(Cause).

learn_where(File:Line) --> { integer(Line), Line > 0 }, !, [ '~w:~w: '-[File, Line] ].
learn_where(File:_) --> !, [ '~w: '-[File] ].
learn_where(W) --> [ '~w: '-[W] ].

learn_cause(unsupported_time(T)) --> !,
    [ '~q: learning data describe one step: only :t and :t+1 are allowed'-[T] ].
learn_cause(time_name_clash(IN, A, B)) --> !,
    [ '~w would stand for both ~q and ~q'-[IN, A, B] ].
learn_cause(value_not_last(P, Pos)) --> !,
    [ '~w: the value must be the last argument (position ~w given)'-[P, Pos] ].
learn_cause(duplicate_target(N)) --> !, [ 'target ~w is declared twice; learned once'-[N] ].
learn_cause(bad_value_spec(S)) --> !,
    [ 'bad values ~q: expected discrete([V,...]), boolean, continuous or count'-[S] ].
learn_cause(declared_twice(P)) --> !, [ '~w is declared twice with other values'-[P] ].
learn_cause(bad_thresholds(T)) --> !, [ 'bad thresholds ~q: a sorted list of distinct numbers'-[T] ].
learn_cause(not_callable(T)) --> !, [ '~q is not a predicate term'-[T] ].
learn_cause(unknown_aggregate(A)) --> !,
    [ 'unknown aggregate ~q: none, count, mean, max, min, mode, antimode (or DreaML''s cnt, avg, maxMod, minMod)'-[A] ].
learn_cause(bad_mode_literal(L)) --> !, [ 'bad mode literal ~q'-[L] ].
learn_cause(bad_rank(R)) --> !, [ 'bad rank ~q: a list of predicate names'-[R] ].
learn_cause(cyclic_rank(P)) --> !,
    [ 'rank/1 lists ~w twice: the order of predicates would be cyclic'-[P] ].
learn_cause(no_base_declaration(N)) --> !,
    [ 'random variable ~w has no base/1 declaration (its argument types)'-[N] ].
learn_cause(unknown_mode_predicate(P)) --> !,
    [ 'mode names ~w, which has no facts, declaration or background clauses'-[P] ].
learn_cause(bad_directive(D)) --> !, [ 'unknown directive ~q'-[D] ].
learn_cause(non_ground_fact(F)) --> !, [ 'a fact must be ground: ~q'-[F] ].
learn_cause(bad_probabilistic_fact(F)) --> !,
    [ 'bad probabilistic fact ~q: P :: Atom with 0 =< P =< 1 and a ground atom'-[F] ].
learn_cause(atom_with_value(P)) --> !,
    [ '~w is an atom elsewhere in the data and has a value here'-[P] ].
learn_cause(key_defined_twice(K, V0, V)) --> !, [ '~q is given two values, ~q and ~q'-[K, V0, V] ].
learn_cause(key_defined_twice(K, other)) --> !, [ '~q is given twice (certain and uncertain)'-[K] ].
learn_cause(repeated_facts(P, N)) --> !,
    [ '~w: ~D facts repeat an earlier one exactly; each is read once'-[P, N] ].
learn_cause(continuous_declared_discrete(K, V, D)) --> !,
    [ '~q ~~= ~q: a number, but the attribute is declared discrete with values ~q (declare it continuous?)'-[K, V, D] ].
learn_cause(value_not_in_domain(K, V, D, DW)) --> !,
    [ '~q ~~= ~q: ~q is not among the declared values ~q'-[K, V, V, D] ],
    (   { DW = F:L } -> [ ' (~w:~w)'-[F, L] ] ; [] ).
learn_cause(not_a_number(K, V)) --> !,
    [ '~q ~~= ~q: not a number, but the attribute is declared continuous'-[K, V] ].
learn_cause(not_a_count(K, V)) --> !,
    [ '~q ~~= ~q: not a count (a non-negative integer)'-[K, V] ].
learn_cause(continuous_distribution_for(K, S)) --> !,
    [ '~q: a continuous distribution for a variable with values ~q'-[K, S] ].
learn_cause(atom_for_random_variable(P)) --> !,
    [ '~w is a random variable with values other than true/false; write K ~~= V'-[P] ].
learn_cause(bad_distribution(D, E)) --> !, [ 'bad distribution ~q: ~q'-[D, E] ].
learn_cause(redefines_builtin(P)) --> !, [ 'background clause redefines the built-in ~w'-[P] ].
learn_cause(mode_for_unknown_target(T)) --> !,
    [ 'mode for ~w, which is not a target (no learn/1 or learn/4) and has no facts'-[T] ].
learn_cause(no_targets) --> !, [ 'no target: declare one with learn/1 (or DreaML''s learn/4)'-[] ].
learn_cause(target_not_random(P)) --> !,
    [ 'target ~w is not a random variable (facts as atoms: declare rv(..., boolean) and examples/2)'-[P] ].
learn_cause(target_without_values(P)) --> !, [ 'target ~w has no values to learn'-[P] ].
learn_cause(target_without_facts(P)) --> !, [ 'target ~w has no facts'-[P] ].
learn_cause(target_type_mismatch(P, T, S)) --> !,
    [ 'target ~w is declared ~w but its values are ~q'-[P, T, S] ].
learn_cause(variable_goal) --> !, [ 'a variable as a goal'-[] ].
learn_cause(random_body(P)) --> !,
    [ '~w draws fresh randomness: not allowed in learning data'-[P] ].
learn_cause(bad_weight(T)) --> !,
    [ 'bad weight ~q: weight(Key, W) with a ground key and a number W > 0'-[T] ].
learn_cause(weighted_twice(K, W0, W)) --> !, [ '~q is given two weights, ~q and ~q'-[K, W0, W] ].
learn_cause(no_types(P)) --> !,
    [ 'a mode with + or - arguments needs the argument types of ~w: declare type(...) (or base/1)'-[P] ].
learn_cause(bad_model(Model, Spec)) --> !,
    [ 'the model ~q does not fit a target with values ~q'-[Model, Spec] ].
learn_cause(no_root_model(T)) --> !,
    [ 'a leaf of ~w reads its root model''s scores, but none was set (learn_root_model/3)'-[T] ].
learn_cause(test_without_facts(Ts, P, Source, Long)) --> !,
    [ 'no test facts of the random variables of ~w (~w)'-[P, Ts] ],
    test_reading(Source, Long).
learn_cause(no_value(Key)) --> !, [ 'the example ~q has no value'-[Key] ].
learn_cause(too_many_worlds(Max)) --> !,
    [ 'a grounding splits into more than ~D partial worlds (uncertain facts it reads); raise max_worlds or make facts certain'-[Max] ].
learn_cause(goal_failed(_)) --> !, [ 'internal: an outcome goal failed'-[] ].
learn_cause(value_not_in_program(K, V, Vs)) --> !,
    [ '~q ~~= ~q: the program gives ~q no probability (its values: ~q)'-[K, V, V, Vs] ].
learn_cause(cyclic_targets(Ts)) --> !,
    [ 'the targets read each other (~w): order them with rank/1'-[Ts] ].
learn_cause(random_variable_as_atom(P)) --> !,
    [ '~w is a random variable: read it with ~~= (K ~~= V)'-[P] ].
learn_cause(C) --> [ '~q'-[C] ].

%   test_reading(+Source, +DreamlForm): how the test data were read, and
%   what to do; DreamlForm are the targets' N/A+1 that the data have as
%   atoms (DreaML's form of a random variable, the value last).
test_reading(declared, _) --> !,
    [ ': the test data were read with their own declarations'-[] ].
test_reading(bias_files(Fs), _) --> !,
    [ ': the test facts were read with the declarations of ~w'-[Fs] ].
test_reading(program(_, Fs), _) --> !,
    [ ': the test facts were read in the dialect and with the declarations of the data the program was learned from (~w); pass the files whose declarations say how they are written with --bias FILE'-[Fs] ].
test_reading(none, Long) -->
    [ ': the test data have no declarations (no bias) and the program does not say what it was learned from, so their facts were read in the project''s own dialect (a random variable''s fact is K ~~= V)'-[] ],
    (   { Long == [] } -> []
    ;   [ '; they hold ~w facts, DreaML''s form (the value last)'-[Long] ]
    ),
    [ '. If they are DreaML''s facts, whose declarations are in the training file, pass that file: ddc evaluate PROGRAM TEST.pl --bias TRAIN.pl'-[] ].

/*  ddc_learn_data.pl -- the learner's data: facts, background knowledge and
    declarative bias read from DC files into a module of their own.

    The structure learner (ddc/learn.pl, library(ddc/learn)) learns distributional clauses from
    relational data with discrete and continuous attributes.  This module
    reads that data, checks it against its declarative bias, and answers
    the questions the learner asks of it: which values a random variable
    has, which literals hold, in one partial possible world at a time.

    Its files are read by the engine's reader of DC files
    (lang/ddc_source.pl: includes, operators, syntax and missing files);
    this module says what their terms mean and runs the final checks; the
    rest lives in modules of one job each, re-exported here:

      ddc_learn_syntax.pl    time-indexed terms renamed; DC bodies as goals
      ddc_learn_bias.pl      the declarative bias; each predicate's kind
      ddc_learn_facts.pl     facts, uncertain facts, background clauses
      ddc_learn_messages.pl  the text of errors and warnings
*/

:- module(ddc_learn_data,
          [ learn_data_load/3,          % +Files, +Options, -Data
            learn_data_free/1,          % +Data
            learn_data_targets/2,       % +Data, -Targets
            learn_data_pred/4,          % +Data, ?Name, ?KeyArity, ?Kind
            example_weight/3,           % +Data, +Key, -Weight
            learn_data_warnings/2,      % +Data, -Warnings
            message_text/2,             % +Message, -Text
            dc_goal/4,                  % +Data, +DCGoal, -Goal, +Where
            internal_key/3,             % +Data, +DCKey, -Key
            dc_term/3,                  % +Data, +Internal, -DCTerm
            pick/3,                     % +Key, +Dist, -Value
            fact_where/3,               % +Data, +Key, -Where
            dist_points/3,              % +Dist, +Samples, -Points
            data_read_terms/3,          % +File, +Mode, -Items
            learn_data_record/4,        % +Data, +Files, +Targets, -Text
            op(700, xfx, ::)            % P :: Atom, a probabilistic atom (the DC
          ]).                           % operators: reexported from ddc_ops)

:- use_module(library(lists)).
:- use_module(library(apply)).
:- use_module(library(assoc)).
:- use_module(library(error)).
:- use_module(library(option)).
:- use_module(library(pairs)).
:- use_module('../lang/ddc_dist').
:- use_module('../lang/ddc_models').
:- use_module('../lang/ddc_source', [source_file/3, source_terms/3]).
:- use_module(ddc_learn_syntax, [time_rename_items/3]).
:- use_module(ddc_learn_bias, [bias_items/2, bias_term/2, finish_preds/2, given_weight/3]).
:- use_module(ddc_learn_facts, [load_item/2, prob_table/2]).
:- reexport(ddc_learn_syntax, [dc_goal/4, internal_key/3, dc_term/3]).
:- reexport(ddc_learn_facts, [pick/3, fact_where/3, dist_points/3]).
:- reexport(ddc_learn_messages, [message_text/2]).
:- reexport('../lang/ddc_ops').                   % data_read_terms/3 reads with them; the learner's
                                        % modules read and write DC terms with them

/** <module> Learning data for the DC structure learner

A data set is one or more files.  Each holds, in any order, facts (the
training data), background knowledge and the declarative bias.  Two
dialects are read; a file that contains any of DreaML's declarations
(base/1, thres/4, randomVariableNames/1, learn/4) is read as DreaML's,
every other file as the project's own (docs/learning.md gives both in
full).

Facts (own dialect), as the paper writes them:

    pos(o1):t ~= 2.3.                 % a random variable's value
    occluded_by(o1, o2):t+1.          % an atom that holds
    colour(o1) ~= red.   on(a, b).    % static facts
    0.7 :: occluded_by(o3, o2):t+1.   % a probabilistic atom
    label(e1) ~ finite([0.7:a, 0.3:b]).   % a probabilistic value

Background knowledge: DC clauses (`h ~ D := Body`, `h := Body`) and plain
Prolog clauses.  Time-indexed terms p(X):t and p(X):t+1 are learned as the
static predicates p_t(X) and p_t1(X) (section 4 of the paper) and mapped
back when clauses are written.

Internally a random variable p(K1,...,Kn) with value V is the Prolog fact
p(K1,...,Kn,V) (DreaML's representation: the value last), an atom is
itself, in a module of its own per data set (the Data handle).  A
probabilistic fact makes that predicate consult the partial world being
proved: pick/3 returns the value the world assigned to the key, or throws
ddcl_need(Key, Dist) so that the caller splits the world on that key.

Errors are error(ddc_learn(Cause, File:Line), _), printed as
`File:Line: cause`.
*/

:- dynamic data_counter/1.
data_counter(0).

                 /*******************************
                 *            LOADING           *
                 *******************************/

%!  learn_data_load(+Files:list, +Options:list, -Data:atom) is det.
%
%   Read the data files into a new module Data.  Options: targets(false)
%   reads data to score a program on (no target need be declared, none
%   need have facts); for such data, when no file has a declaration (a
%   test file of facts only), bias_files(Fs) gives the declarations that
%   say how their facts are read (those of the files Fs, in their
%   dialect), else program(File) takes them from the record of the
%   program File was learned from (learn_data_record/4).  Every fact is
%   checked against the bias: a value outside a
%   declared domain, a non-number for a continuous attribute, a key with
%   two values, a mode that names an unknown predicate, a target without
%   facts, a rank that lists a predicate twice are errors naming the file
%   and line.  A file may include another (`:- include(File).`, relative
%   to it), and declare operators for the rest of its text (`:- op/3`).
%
%   @error ddc_learn(Cause, File:Line) for what the data say;
%   the reader's ISO errors (lang/ddc_source.pl) for a file that cannot be
%   read: existence_error(source_sink, Spec), syntax_error(Message), ...
learn_data_load(Files, Options, Data) :-
    must_be(list, Files),
    must_be(list, Options),
    (   Files == [] -> domain_error(non_empty_list, Files) ; true ),
    maplist(resolve_data_file, Files, Paths),
    new_data_module(Data),
    (   option(targets(false), Options) -> Check = false ; Check = true ),
    catch(load_into(Data, Paths, Check, Options), E, ( learn_data_free(Data), throw(E) )).

resolve_data_file(Spec, Path) :-
    source_file(Spec, [prefer(exact)], Path).

new_data_module(M) :-
    with_mutex(ddc_learn_data,
               ( retract(data_counter(N0)), N is N0+1, assertz(data_counter(N)) )),
    atom_concat('ddc_learn_data_', N, M),
    set_module(M:base(system)),
    set_module(M:class(temporary)),
    M:use_module(library(lists)),
    M:use_module(library(apply)),
    module_property(ddc_models, file(ModelsFile)),
    M:use_module(ModelsFile),
    maplist(declare_dynamic(M), ['$ddcl_pred'/3, '$ddcl_type'/5, '$ddcl_base'/3,
                                 '$ddcl_dreaml'/3, '$ddcl_timed'/3, '$ddcl_mode'/6,
                                 '$ddcl_thresholds'/2, '$ddcl_rank'/2, '$ddcl_target'/4,
                                 '$ddcl_examples'/4, '$ddcl_background'/3, '$ddcl_file'/2,
                                 '$ddcl_warning'/1, '$ddcl_prob_pred'/2, '$ddcl_bg_rv'/2,
                                 '$ddcl_root_model'/2, '$ddcl_declaration'/3,
                                 '$ddcl_bias_source'/1]).

declare_dynamic(M, PI) :- dynamic(M:PI).

%!  learn_data_free(+Data:atom) is det.
%
%   Forget a data set (its module and everything learned about it).
learn_data_free(M) :-
    (   current_module(M), sub_atom(M, 0, _, _, ddc_learn_data_)
    ->  forall(( current_predicate(M:N/A), functor(H, N, A),
                 \+ predicate_property(M:H, imported_from(_)) ),
               abolish(M:N/A))
    ;   true
    ).

load_into(M, Paths, Check, Options) :-
    maplist(read_file_items, Paths, ItemLists0),
    (   \+ ( member(Is, ItemLists0), member(item(T, _, D, _), Is), bias_term(D, T) )
    ->  (   Check == false, reading_bias(Options, Dialect, Extra, Source)
        ->  maplist(maplist(set_dialect(Dialect)), ItemLists0, ItemLists)
        ;   ItemLists = ItemLists0, Extra = [], Source = none
        ),
        assertz(M:'$ddcl_bias_source'(Source))
    ;   ItemLists = ItemLists0, Extra = []
    ),
    append([Extra|ItemLists], Items0),
    maplist(file_dialect, ItemLists, Dialects),
    pairs_keys_values(FDs, Paths, Dialects),
    forall(member(F-D, FDs), assertz(M:'$ddcl_file'(F, D))),
    forall(( member(item(T, _, D, W), Items0), reading_declaration(D, T) ),
           assertz(M:'$ddcl_declaration'(D, T, W))),
    time_rename_items(M, Items0, Items),
    bias_items(M, Items),
    finish_preds(M, Items),
    forall(member(I, Items), load_item(M, I)),
    forall(( member(item(T, Vs, _, W), Items), M:'$ddcl_background'(_, _, W) ),
           assertz(M:'$ddcl_named'(W, T-Vs))),
    check_bias(M, Check).

%   Items: item(Term, VarNames, Dialect, File:Line).
read_file_items(Path, Items) :-
    data_read_terms(Path, own, Items0),
    dialect_of(Path, Items0, D),
    maplist(set_dialect(D), Items0, Items).

set_dialect(D, item(T, Vs, _, W), item(T, Vs, D, W)).

file_dialect([item(_, _, D, _)|_], D) :- !.
file_dialect([], own).

%   reading_declaration(+Dialect, +Term): a declaration that says how facts
%   are read (which predicates are random variables, their values, their
%   argument types, the groundings of a target given as atoms), as opposed
%   to the search's (modes, targets, ranks, thresholds).
reading_declaration(dreaml, T) :-
    functor(T, N, A), memberchk(N/A, [base/1, thres/4, randomVariableNames/1]).
reading_declaration(own, T) :-
    functor(T, N, A), memberchk(N/A, [type/1, rv/1, rv/2, examples/2]).

%   reading_bias(+Options, -Dialect, -Items, -Source): the declarations to
%   read test facts by, when their files have none: those of the files of
%   bias_files(Fs), or of the record of the program of program(File).
reading_bias(Options, D, Items, bias_files(Fs)) :-
    option(bias_files(Fs0), Options), Fs0 \== [], !,
    maplist(resolve_data_file, Fs0, Fs),
    maplist(read_file_items, Fs, Lists),
    Lists = [L0|_], file_dialect(L0, D),
    findall(I, ( member(L, Lists), member(I, L), I = item(T, _, D, _),
                 reading_declaration(D, T) ), Items).
reading_bias(Options, D, Items, program(P, Files)) :-
    option(program(P0), Options),
    resolve_data_file(P0, P),
    program_record(P, learned_from(D, Files, _, Decls), Line),
    findall(item(T, [], D, P:Line), ( member(T, Decls), reading_declaration(D, T) ), Items).

%   program_record(+ProgramFile, -Record, -Line:integer) is semidet.
%
%   Record is the learned_from(Dialect, Files, Targets, Declarations) fact
%   of a learned program (learn_data_record/4) and Line its line; fails if
%   the program has none.
program_record(P, learned_from(D, Fs, Ts, Ds), Line) :-
    data_read_terms(P, own, Items),
    member(item(learned_from(D, Fs, Ts, Ds), _, _, _:Line), Items),
    atom(D), is_list(Fs), is_list(Ds), !.

%!  learn_data_record(+Data, +Files:list, +Targets:list(atom), -Text:string) is det.
%
%   The record a learned program keeps of its data, as the DC text of a
%   fact learned_from(Dialect, Files, Targets, Declarations): the dialect
%   of the data (dreaml if a file is DreaML's), the data files (as given),
%   the targets (their DC keys, e.g. occluder(_, _):t+1, of the internal
%   names Targets) and the declarations that say how the facts are read
%   (reading_declaration/2: base/1, thres/4, randomVariableNames/1; type/1,
%   rv/1,2, examples/2).  `ddc evaluate` reads test files that have no
%   declarations by them.
learn_data_record(M, Files, Targets, Text) :-
    (   M:'$ddcl_file'(_, dreaml) -> D = dreaml ; D = own ),
    findall(T, M:'$ddcl_declaration'(D, T, _), Ds),
    findall(K, ( member(N, Targets), M:'$ddcl_target'(N, A, _, _),
                 length(As, A), K0 =.. [N|As], dc_term(M, K0, K) ), Ks),
    maplist([F, A]>>( atom(F) -> A = F ; atom_string(A, F) ), Files, FAs),
    copy_term(t(FAs, Ks, Ds), t(FAs1, Ks1, Ds1)),
    maplist([T]>>numbervars(T, 0, _, [singletons(true)]), Ks1),
    maplist([T]>>numbervars(T, 0, _, [singletons(true)]), Ds1),
    with_output_to(string(Text),
                   ( format('learned_from(~q, ', [D]), record_term(FAs1), write(','), nl,
                     write('    '), record_term(Ks1), write(','), nl,
                     write('    ['),
                     foldl([T, Sep0, Sep]>>( write(Sep0), record_term(T), Sep = ',\n      ' ),
                           Ds1, ' ', _),
                     write(']).') )).

record_term(T) :-
    write_term(T, [quoted(true), numbervars(true), spacing(next_argument),
                   module(ddc_learn_data)]).

dialect_of(_, Items, dreaml) :-
    member(item(T, _, _, _), Items),
    ( T = base(_) ; T = thres(_, _, _, _) ; T = randomVariableNames(_) ; T = learn(_, _, _, _) ),
    !.
dialect_of(_, _, own).

%!  data_read_terms(+File, +Dialect, -Items) is det.
%
%   Items is item(Term, VariableNames, Dialect, File1:Line) for each clause
%   of File, read with the DC operators (and `::`) by the reader of DC files
%   (lang/ddc_source.pl): `:- include(Spec).` is replaced by the clauses of
%   the file it names (File1 that file), `:- op/3` applies to the rest of
%   the file.  The bracket depth is not scanned first, as the engine's
%   programs are (it would cost more than reading large files of facts).
%
%   @error the reader's (lang/ddc_source.pl): existence_error(source_sink, Spec),
%   syntax_error(Message), permission_error(include, source_sink, File), each
%   with context(ddc_source:source_terms/3, File:Line).
data_read_terms(File, Dialect, Items) :-
    source_terms(File, [module(ddc_learn_data), check_nesting(false)], Sources),
    maplist(data_item(Dialect), Sources, Items).

data_item(D, src(T, Vs, File, Line), item(T, Vs, D, File:Line)).

                 /*******************************
                 *        FINAL CHECKS          *
                 *******************************/

%   check_bias(+M): every predicate a mode names is known, every target
%   has facts, the values of undeclared random variables give their kind.
check_bias(M, false) :- !,
    infer_specs(M),
    materialise_derived(M).
check_bias(M, true) :-
    infer_specs(M),
    materialise_derived(M),
    forall(M:'$ddcl_mode'(_, _, _, C, L, W), ( mode_preds_known(M, C, W), mode_preds_known(M, L, W) )),
    forall(M:'$ddcl_target'(N, A, _, W), check_target(M, N, A, W)),
    forall(( M:'$ddcl_mode'(_, TN/_, _, _, _, W), TN \== any,
             \+ M:'$ddcl_target'(TN, _, _, _), \+ M:'$ddcl_pred'(TN, _, _) ),
           throw(error(ddc_learn(mode_for_unknown_target(TN), W), _))),
    (   M:'$ddcl_target'(_, _, _, _) -> true
    ;   M:'$ddcl_file'(F, _) -> throw(error(ddc_learn(no_targets, F:0), _))
    ).

infer_specs(M) :-
    forall(( M:'$ddcl_pred'(N, A, rv(S)), ( S == infer ; S == infer_numeric ) ),
           ( rv_values(M, N, A, Vs),
             inferred_spec(S, Vs, Spec),
             retract(M:'$ddcl_pred'(N, A, rv(S))),
             assertz(M:'$ddcl_pred'(N, A, rv(Spec))) )),
    forall(( M:'$ddcl_pred'(N, A, rv(discrete([true, false]))),
             M:'$ddcl_thresholds'(N/A, _) ),
           retractall(M:'$ddcl_thresholds'(N/A, _))).

%   rv_values(+M, +N, +A, -Values): the distinct values of N/A in the facts
%   (certain and uncertain ones).
rv_values(M, N, A, Vs) :-
    length(Ks, A), append(Ks, [V], As), F =.. [N|As],
    findall(V, clause(M:F, true), Vs1),
    prob_table(N, PN), append(Ks, [D], PAs), PF =.. [PN|PAs],
    findall(V2, ( M:'$ddcl_prob_pred'(N, A), clause(M:PF, true), dist_discrete(D),
                  dist_support(D, Ps), member(_-V2, Ps) ), Vs2),
    append(Vs1, Vs2, Vs0),
    sort(Vs0, Vs).

inferred_spec(_, [], any) :- !.
inferred_spec(_, Vs, continuous) :- maplist(number, Vs), !.
inferred_spec(_, Vs, discrete([true, false])) :- subtract(Vs, [false, true], []), !.
inferred_spec(infer, Vs, discrete(Vs)) :- maplist(atomic, Vs), !.
inferred_spec(_, _, any).

%   materialise_derived(+M): a derived atom of the background knowledge
%   that some mode reads (DreaML's districtClientAccount(D, C, A) :-
%   clientDistrict(C, D, true), hasAccount(C, A, true)) is replaced by its
%   solutions, when they do not depend on uncertain facts and number at
%   most 200,000: a call with only its last argument bound then takes an
%   index instead of a join over every client (measured on FinancialData.pl:
%   13.7 s -> 0.05 s for one candidate at the root of stdMonthW).  The
%   rules stay in '$ddcl_background'/3 for the learned program.
materialise_derived(M) :-
    findall(N/A, ( M:'$ddcl_mode'(_, _, _, C, L, _), member(Lit, [C, L]), Lit \== none,
                   conj_member(Lit, G), functor(G, N, A),
                   learn_data_pred(M, N, A, atom),
                   functor(H, N, A), M:'$ddcl_background'(H0, _, _), \+ H0 \= H ), Ps0),
    sort(Ps0, Ps),
    forall(member(P, Ps), ignore(materialise(M, P))).

conj_member((A, B), G) :- !, ( conj_member(A, G) ; conj_member(B, G) ).
conj_member(G, G).

materialise(M, N/A) :-
    Cap = 200000,
    Cap1 is Cap+1,
    functor(H, N, A),
    catch(( empty_assoc(E), b_setval(ddcl_assign, E),
            once(findnsols(Cap1, H, M:H, Hs)) ),
          _, fail),
    length(Hs, L), L =< Cap,
    sort(Hs, Facts),
    retractall(M:H),
    forall(member(F, Facts), assertz(M:F)).

mode_preds_known(_, none, _) :- !.
mode_preds_known(M, (A, B), W) :- !, mode_preds_known(M, A, W), mode_preds_known(M, B, W).
mode_preds_known(M, L, W) :-
    functor(L, N, Ar),
    (   A1 is Ar-1, M:'$ddcl_pred'(N, A1, rv(_)) -> true
    ;   M:'$ddcl_pred'(N, Ar, atom) -> true
    ;   functor(H, N, Ar), predicate_property(M:H, defined), \+ predicate_property(M:H, imported_from(_))
    ->  true
    ;   throw(error(ddc_learn(unknown_mode_predicate(N/Ar), W), _))
    ).

%   has_facts(+M, +N, +A): the random variable N/A has a certain or an
%   uncertain fact.
has_facts(M, N, A) :-
    length(Ks, A), append(Ks, [_], As), F =.. [N|As],
    (   clause(M:F, true) -> true
    ;   M:'$ddcl_prob_pred'(N, A)
    ), !.

check_target(M, N, A, W) :-
    (   M:'$ddcl_pred'(N, A, rv(Spec)) -> true
    ;   throw(error(ddc_learn(target_not_random(N/A), W), _))
    ),
    (   Spec == any -> throw(error(ddc_learn(target_without_values(N/A), W), _)) ; true ),
    (   M:'$ddcl_examples'(N/A, _, _, _) -> true
    ;   has_facts(M, N, A) -> true
    ;   throw(error(ddc_learn(target_without_facts(N/A), W), _))
    ),
    (   M:'$ddcl_target'(N, A, dreaml(Type), _)
    ->  (   Type == discrete, Spec = discrete(_) -> true
        ;   Type == continuous, ( Spec == continuous ; Spec == count ) -> true
        ;   throw(error(ddc_learn(target_type_mismatch(N/A, Type, Spec), W), _))
        )
    ;   true
    ).

                 /*******************************
                 *            QUERIES           *
                 *******************************/

%!  learn_data_targets(+Data, -Targets:list) is det.
%
%   Targets is a list of target(Name, KeyArity, Spec, VarNames, Where) in
%   the order of the files.
learn_data_targets(M, Targets) :-
    findall(target(N, A, Spec, Names, W),
            ( M:'$ddcl_target'(N, A, How, W), M:'$ddcl_pred'(N, A, rv(Spec)),
              ( How = own(Names) -> true ; length(Names, A), maplist(=('_'), Names) ) ),
            Targets).

%!  example_weight(+Data, +Key, -Weight) is det.
%
%   The weight of a grounding (weight(Key, W) in the data; 1 when none is
%   given): how many examples it stands for.
example_weight(M, K, W) :-
    (   given_weight(M, K, W0) -> W = W0 ; W = 1.0 ).

%!  learn_data_pred(+Data, ?Name, ?KeyArity, ?Kind) is nondet.
%
%   Kind is rv(Spec) (Spec: discrete(Domain), continuous, count, any) or
%   atom.
learn_data_pred(M, N, A, K) :-
    M:'$ddcl_pred'(N, A, K).

%!  learn_data_warnings(+Data, -Warnings:list(string)) is det.
%
%   The data's warnings, each as a line `File:Line: cause`.
learn_data_warnings(M, Ws) :-
    findall(T, ( M:'$ddcl_warning'(W), message_text(ddc_learn_warning(W), T) ), Ws).

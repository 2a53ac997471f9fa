/*  ddc_read.pl -- what the terms of a DC program file mean.

    Part of the DDC engine (ddc.pl is the module users load).  The engine's
    client of the reader of DC files (ddc_source.pl, which opens the file,
    follows its includes and reports what keeps it from being read): sorts a
    program's terms into its items (random variable and derived clauses,
    plain Prolog clauses) and its directives, each remembering its line so
    that every error names File:Line.
*/

:- module(ddc_read,
          [ resolve_file/2,             % +Spec, -File
            read_program/2,             % +File, -Terms
            classify_program/6,         % +File, +Module, +Terms, -Items, -Options, -DirectiveClauses
            load_error/3,               % +Error, +Culprit, +Where
            dist_sugar/2,               % +Dist, -Dist1
            spec_list/2,                % +Spec, -List
            item_id/2,                  % +Item, -Id
            item_line/2                 % +Item, -Line
          ]).

:- use_module(library(lists)).
:- use_module(library(aggregate)).
:- use_module(ddc_source, [source_file/3, source_terms/3]).
:- use_module('../compat/dc_compat_load').   % the original DC's option directives and arithmetic

:- use_module(ddc_ops).

%   Arithmetic compiled to virtual-machine instructions (local to this
%   file; see ddc.pl).
:- set_prolog_flag(optimise, true).

/** <module> The items of a DC program file

An item is one of
  - rv(Id, X, Kind, Dist, Body, Line): a random variable clause
  - der(Id, X, Kind, Body, Line): a derived atom's clause
  - plain(Clause, Line): a clause of plain Prolog
Kind is u (untimed), state (h:t), trans (h:t+1), fixed(N) (h:N) or
persist (added by a persistent/1 directive).  Ids number the random
variable and derived clauses in file order from 1.
*/

%!  resolve_file(+Spec, -File:atom) is det.
%
%   File is the absolute name of the program file Spec (a Prolog file
%   first, then any file).
%
%   @error existence_error(source_sink, Spec) if there is none (ddc_source.pl).
resolve_file(Spec, File) :-
    source_file(Spec, [prefer(prolog)], File).

%!  read_program(+File:atom, -Terms:list) is det.
%
%   Terms is a list of t(Term, Line): the terms of the program File as
%   the reader of DC files (ddc_source.pl) reads them, with the engine's
%   operators: `:- include(Spec).` replaced by the included file's terms,
%   `:- op/3` applied to the rest of the file only.  An included term's
%   Line is Included:Line, so that every error about it names the
%   included file and its line.
%
%   @error the reader's (ddc_source.pl): existence_error(source_sink, Spec),
%   syntax_error(Message), permission_error(include, source_sink, File), each
%   with context(ddc_source:source_terms/3, File:Line).
read_program(File, Terms) :-
    source_terms(File, [module(ddc), variable_names(false)], Sources),
    program_terms(Sources, File, Terms).

program_terms([], _, []).
program_terms([src(T, _, F, Line)|Ss], File, [t(T, L)|Ts]) :-
    (   F == File -> L = Line ; L = F:Line ),
    program_terms(Ss, File, Ts).

%!  classify_program(+File, +Module, +Terms, -Items, -Options, -DirectiveClauses) is det.
%
%   The items of the program read from File (Terms, as read_program/2
%   gives them), with the clauses its persistent/1 directives add; Options
%   the directives' options (first(Spec), persistent(Spec), facts(Spec),
%   the original's set_options/1, ...) and DirectiveClauses the clauses
%   they add to Module.
classify_program(File, M, Terms0, Items, Opts, DirClauses) :-
    original_program(Terms0, Terms),    % `X is random`, logfinite([W:_]) (dc_compat_load.pl)
    classify_items(Terms, File, 1, Items1, Dirs),
    directives_options(Dirs, File, M, Opts, DirClauses),
    add_persistence(Opts, Items1, Items).

classify_items([], _, _, [], []).
classify_items([t(T, L)|Ts], File, Id, Items, Dirs) :-
    (   var(T)
    ->  throw(error(ddc(unbound_head, File:L), _))
    ;   ( T = (:- D) ; T = (_ :- D) ), var(D)
    ->  throw(error(ddc(unbound_body, File:L), _))
    ;   sub_term(Z, T), compound(Z), compound_name_arity(Z, _, 0)
    ->  throw(error(ddc(zero_arity_compound(Z), File:L), _))
    ;   true
    ),
    (   T = (:- D)
    ->  Items = Items1, Dirs = [D-L|Dirs1], Id1 = Id
    ;   classify(T, Id, L, File, Item)
    ->  Items = [Item|Items1], Dirs = Dirs1, Id1 is Id+1
    ;   Items = [plain(T, L)|Items1], Dirs = Dirs1, Id1 = Id
    ),
    classify_items(Ts, File, Id1, Items1, Dirs1).

classify(T pr _, Id, L, File, Item) :- !,
    classify(T, Id, L, File, Item).
classify((H ~ D := B), Id, L, File, rv(Id, X, K, D1, B, L)) :- !,
    head_time(H, X, K, File, L), dist_sugar(D, D1).
classify((H ~ D <- B), Id, L, File, rv(Id, X, K, D1, B, L)) :- !,
    head_time(H, X, K, File, L), dist_sugar(D, D1).
classify((H ~ D), Id, L, File, rv(Id, X, K, D1, true, L)) :- !,
    head_time(H, X, K, File, L), dist_sugar(D, D1).
classify((H := B), Id, L, File, der(Id, X, K, B, L)) :- !,
    head_time(H, X, K, File, L),
    check_left_recursion(H, B, File:L).
classify((H <- B), Id, L, File, der(Id, X, K, B, L)) :- !,
    head_time(H, X, K, File, L),
    check_left_recursion(H, B, File:L).

%   check_left_recursion(+Head, +Body, +Where): a derived clause whose body
%   starts by proving its own head again (`p := p.`, `p(X) := p(X), q(X).`,
%   `h:t+1 := h:t+1.`) never terminates: the program's error at load, not
%   a stack overflow at run time.
check_left_recursion(H, B, Where) :-
    first_goal(B, G),
    nonvar(G), G == H, !,
    throw(error(ddc(left_recursion(H), Where), _)).
check_left_recursion(_, _, _).

first_goal(B, G) :- var(B), !, G = B.
first_goal((A, _), G) :- !, first_goal(A, G).
first_goal(B, B).

head_time(H, _, _, File, L) :-
    var(H), !,
    throw(error(ddc(unbound_head, File:L), _)).
head_time(X:(T+K), X, trans, _, _) :- T == t, K == 1, !.
head_time((X:T)+1, X, trans, _, _) :- T == t, !.
head_time(X:T, X, state, _, _) :- T == t, !.
head_time(X:N, X, fixed(N), _, _) :- integer(N), !.
head_time(current(X), X, state, _, _) :- nonvar(X), !.
head_time(next(X), X, trans, _, _) :- nonvar(X), !.
head_time(prior(X), X, fixed(0), _, _) :- nonvar(X), !.
head_time(H, _, _, File, L) :-
    \+ callable(H), !,
    throw(error(ddc(bad_head(H), File:L), _)).
head_time(H, H, u, _, _).

%   Distribution sugar (done at compile time).
dist_sugar(D, D) :- var(D), !.
dist_sugar(finite(L), finite(L)) :- is_list(L), !.
dist_sugar(finite(L), finite(L)) :- var(L), !.
dist_sugar(D, finite(L)) :-
    compound(D), compound_name_arguments(D, finite, Args), Args \= [], \+ (Args = [A], is_list(A)),
    forall(member(A, Args), nonvar(A)), forall(member(A, Args), A = _:_), !,
    L = Args.
dist_sugar(uniform(A, B), contUniform(A, B)) :- !.
dist_sugar(uniform(L), uniform(Lo:Hi)) :-   % a constant list Lo, Lo+1, ..., Hi: the
    integer_run(L, Lo, Hi), Hi > Lo, !.    % same draws, without walking the list
dist_sugar(D, D).

%   integer_run(+List, -First, -Last): List is First, First+1, ..., Last.
integer_run(L, Lo, Hi) :-
    is_list(L), L = [Lo|T], integer(Lo),
    integer_run_(T, Lo, Hi).

integer_run_([], Hi, Hi).
integer_run_([X|T], Prev, Hi) :-
    integer(X), X =:= Prev + 1,
    integer_run_(T, X, Hi).

%   Directives.
directives_options([], _, _, [], []).
directives_options([D-L|Ds], File, M, Opts, Cls) :-
    directive(D, File, L, M, Opts, Opts1, Cls, Cls1),
    directives_options(Ds, File, M, Opts1, Cls1).

directive(first_applicable(S), _, _, _, [first(S)|O], O, C, C) :- !.
directive(persistent(S), _, _, _, [persistent(S)|O], O, C, C) :- !.
directive(use_module(library(_)), _, _, _, O, O, C, C) :- !.   % libraries are visible anyway
directive(use_module(library(_), _), _, _, _, O, O, C, C) :- !.
directive(use_module(_), _, _, _, O, O, C, C) :- !.           % the original's own files
directive(use_module(_, _), _, _, _, O, O, C, C) :- !.
directive(ensure_loaded(_), _, _, _, O, O, C, C) :- !.
directive(initialization(_), _, _, _, O, O, C, C) :- !.        % the originals' test runners
directive(initialization(_, _), _, _, _, O, O, C, C) :- !.
directive(D, File, L, _, O0, O, C, C) :-
    original_directive(D, File:L, Os), !,      % set_options/1, ... (dc_compat_load.pl)
    append(Os, O, O0).
directive(dynamic(S), _, _, _, [facts(S)|O], O, C, C) :- !.   % read from a filter step's facts
directive(discontiguous(_), _, _, _, O, O, C, C) :- !.
directive(op(_, _, _), _, _, _, O, O, C, C) :- !.     % applied while reading (ddc_source.pl)
directive(D, File, L, _, _, _, _, _) :-
    throw(error(ddc(bad_directive(D), File:L), _)).

%   persistent(Name/Arity): for each declared h, add after the program's
%   clauses  h:t+1 ~ val(V) := h:t ~= V  (random variable) or
%   h:t+1 := h:t (derived atom).
add_persistence(Opts, Items0, Items) :-
    findall(S, ( member(persistent(Spec), Opts), spec_list(Spec, Ss), member(S, Ss) ), Specs),
    (   Specs == []
    ->  Items = Items0
    ;   last_id(Items0, Id0),
        persistence_items(Specs, Items0, Id0, New),
        append(Items0, New, Items)
    ).

spec_list(Spec, L) :- is_list(Spec), !, L = Spec.
spec_list((A,B), L) :- !, spec_list(A, LA), spec_list(B, LB), append(LA, LB, L).
spec_list(S, [S]).

last_id(Items, Id) :-
    aggregate_all(max(I), ( member(It, Items), item_id(It, I) ), Max), !,
    ( Max == -inf -> Id = 0 ; Id = Max ).
last_id(_, 0).

item_id(rv(Id, _, _, _, _, _), Id).
item_id(der(Id, _, _, _, _), Id).

persistence_items([], _, _, []).
persistence_items([N/A|Ss], Items, Id0, New) :-
    functor(X, N, A),
    Id is Id0+1,
    (   member(rv(_, X0, _, _, _, L), Items), \+ X0 \= X
    ->  New = [rv(Id, X, persist, val(V), (X:t ~= V), L)|New1]
    ;   member(der(_, X0, _, _, L), Items), \+ X0 \= X
    ->  New = [der(Id, X, persist, X:t, L)|New1]
    ;   New = [rv(Id, X, persist, val(V), (X:t ~= V), 0)|New1]
    ),
    persistence_items(Ss, Items, Id, New1).

item_line(rv(_, _, _, _, _, L), L).
item_line(der(_, _, _, _, L), L).

%!  load_error(+Error, +Culprit, +Where) is det.
%
%   Rethrows Error of loading Culprit as the program's error at Where
%   (an engine error that already names a line keeps it).
load_error(error(ddc(C, W0), _), _, Where) :- !,
    (   W0 = _:L0, ( integer(L0), L0 > 0 ; L0 = _:_ ) -> W = W0 ; W = Where ),
    throw(error(ddc(C, W), _)).
load_error(E, _, Where) :-
    throw(error(ddc(prolog_error(E), Where), _)).

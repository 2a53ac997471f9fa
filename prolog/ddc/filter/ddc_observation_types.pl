/*  ddc_observation_types.pl -- is an observation's value of a type the program can weigh?

    The bridge (ddc_bridge.pl) checks each weighted observation H ~= V of a step against
    the filter's program before the step: a value of the wrong type (an atom or a tuple
    where the program's clauses for H weigh a number, a list of a million numbers where
    they weigh three, the atom nan, a NaN) is an error naming the item, where the engine
    alone would give every particle the weight 0 (a value outside a distribution's
    support, ddc_dist.pl).
*/

:- module(ddc_observation_types,
          [ observation_type_error/4   % +Filter, +Observations, -I, -Message
          ]).

:- use_module(library(apply)).
:- use_module(library(lists)).
:- use_module('../lang/ddc_programs', [program_items/2]).

/** <module> The types of observation values a program weighs

Each random-variable clause of the program whose head is observation(H) weighs values of a
*kind*, read from its distribution term:

| distribution | kind |
|---|---|
| gaussian(M, V), M a number (or unbound and V a number) | a number |
| gaussian([M1,...,Mk], C) | k numbers: a tuple (X1,...,Xk) or a list (a number when k = 1) |
| gaussian(M, C) otherwise, indepGaussians, optimalProposal, indepOptimalProposals | numbers |
| contUniform, beta, gamma, invgamma, student, poisson, exponential | a number |
| dirichlet([A1,...,Ak]) | k numbers |
| finite, propfinite, logfinite, uniform, bool, val, and the rest | anything |

The numbers must be finite.  An observation H ~= V is of the wrong type when at least one
clause for H has a kind other than "anything" and no clause for H weighs V by its kind.  A
clause that weighs anything, val(_) of a fresh variable above all (a program's "nothing
known yet" case), does not make every value right: it would otherwise hide a wrong type
from the clauses that do weigh it.
*/

%!  observation_type_error(+Filter, +Observations:list, -I:integer, -Message:string) is semidet.
%
%   The first weighted observation (H ~= V, H mostly observation(X)) in Observations, at
%   1-based place I, whose value V no clause of Filter's program for H weighs by its type (see the module's
%   documentation); Message says what the clauses take.  Fails when every value is of a
%   type some clause weighs, or when the filter's program cannot be found.
observation_type_error(F, Obs, I, Message) :-
    catch(ddc_filter:filter_engine_(F, _, M, File), _, fail),
    catch(program_items(M, Items), _, fail),
    nth1(I, Obs, H ~= V),
    findall(Kind-Line, ( member(rv(_, H0, _, Dist, _, Line), Items),
                         \+ H0 \= H,
                         dist_kind(Dist, Kind) ), Kinds0),
    exclude([any-_]>>true, Kinds0, Kinds),
    Kinds \== [],
    \+ ( member(Kind-_, Kinds), takes(Kind, V) ),
    !,
    file_base_name(File, Base),
    maplist(kind_text(Base), Kinds, Texts),
    atomic_list_concat(Texts, ' or ', Takes),
    value_text(V, Got),
    format(string(Message), "a value of the wrong type: ~q takes ~w, not ~w",
           [H, Takes, Got]).

%   dist_kind(+Dist, -Kind): number, numbers(K), numbers, or any.
dist_kind(D, any) :- var(D), !.
dist_kind(gaussian(M, V), Kind) :- !,
    (   number(M) -> Kind = number
    ;   is_list(M) -> length(M, K), Kind = numbers(K)
    ;   var(M), number(V) -> Kind = number
    ;   Kind = numbers
    ).
dist_kind(dirichlet(As), Kind) :- !,
    ( is_list(As) -> length(As, K), Kind = numbers(K) ; Kind = numbers ).
dist_kind(D, numbers) :-
    compound(D), compound_name_arity(D, Name, _),
    memberchk(Name, [indepGaussians, optimalProposal, indepOptimalProposals]), !.
dist_kind(D, number) :-
    compound(D), compound_name_arity(D, Name, _),
    memberchk(Name, [contUniform, beta, gamma, invgamma, student, poisson, exponential]), !.
dist_kind(_, any).

%   takes(+Kind, +Value)
takes(number, V) :- finite(V).
takes(numbers(1), V) :- finite(V), !.
takes(numbers(K), V) :- value_numbers(V, Xs), length(Xs, K), maplist(finite, Xs).
takes(numbers, V) :- finite(V), !.
takes(numbers, V) :- value_numbers(V, Xs), Xs \== [], maplist(finite, Xs).

finite(X) :- number(X), ( integer(X) -> true ; float_class(X, C), C \== nan, C \== infinite ).

%   value_numbers(+Value, -List): a list, or a comma tuple as a list.
value_numbers(V, V) :- is_list(V), !.
value_numbers((A, B), [A|T]) :- !, comma_list(B, T).

comma_list((A, B), [A|T]) :- !, comma_list(B, T).
comma_list(A, [A]).

kind_text(_, Kind-(Included:Line), Text) :- !,     % a clause of an included file
    file_base_name(Included, Base),
    kind_text(Base, Kind-Line, Text).
kind_text(File, Kind-Line, Text) :-
    kind_words(Kind, Words),
    format(atom(Text), "~w (~w:~w)", [Words, File, Line]).

kind_words(number, 'a finite number').
kind_words(numbers(1), 'a finite number').
kind_words(numbers(K), Words) :- integer(K), K > 1,
    format(atom(Words), '~d finite numbers, a tuple (X1,...) or a list', [K]).
kind_words(numbers, 'finite numbers').

%   value_text(+V, -Text): V, or for a long list or tuple its length.
value_text(V, Text) :-
    value_numbers(V, Xs), length(Xs, N), N > 10, !,
    (   is_list(V) -> What = 'a list' ; What = 'a tuple' ),
    format(atom(Text), '~w of ~D values', [What, N]).
value_text((A, B), Text) :- !,
    format(atom(Text), '(~q)', [(A, B)]).
value_text(V, Text) :-
    format(atom(Text), '~q', [V]).

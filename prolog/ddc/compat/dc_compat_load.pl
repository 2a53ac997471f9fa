/*  dc_compat_load.pl -- what the engine's reader needs to read programs
    written for the original Distributional Clauses system (DC/DCPF, YAP).

    Two things, both called from ddc_read.pl while it reads a program:
    the original's option directives (set_options/1, set_inference/1, ...),
    accepted with a warning where an option changes nothing in this engine,
    and the original's arithmetic (`X is random`), rewritten to SWI-Prolog's.
    The original's entry points (query/7, init_particle/1, ...) are in
    dc_compat.pl.
*/

:- module(dc_compat_load,
          [ original_directive/3,       % +Directive, +File:Line, -Options
            original_arithmetic/2,      % +Term0, -Term
            original_program/2          % +Items0, -Items
          ]).

:- use_module(library(lists)).
:- use_module(library(error)).
:- use_module(library(terms), [mapsubterms/3]).

:- dynamic warned_/2.                  % warned_(Directive, File:Line)

/** <module> Reading programs of the original DC system

The original programs start with

    :- use_module('../distributionalclause.pl').
    :- use_module('../random/sampling.pl').
    :- set_options(default), set_inference(backward(lw)).
    :- initialization(init).

ddc_read.pl ignores the use_module/1 and initialization/1 directives itself;
this module accepts the option setters, alone or in a conjunction.  An
option whose value is what this engine does anyway is silent; one that the
original honoured and this engine does not (another inference mode, lifted
inference, Rao-Blackwellisation, debug printing, no copying of h:t clauses
to t+1) is accepted with one warning naming the file and line, and the
answers are this engine's (docs/dc-compat.md lists the differences).  An
option value the original did not know is an error.
*/

%!  original_directive(+Directive:callable, +Where:compound, -Options:list) is semidet.
%
%   Directive is one of the original's option setters, or a conjunction of
%   them; Where is File:Line of the directive.  Prints a warning for each
%   option that changes nothing here.  Options are the program options of
%   ddc.pl it stands for: set_options/1 (which every program of the
%   original calls) gives first(all), the original's rule that the first
%   clause (in file order) whose body holds defines a variable, where
%   ddc.pl would otherwise refuse two clauses that apply in one world, and
%   facts([action/1, deltaT/1, dc_observation/2]), the facts the
%   original's filter asserts at each step (as `:- dynamic(action/1).`
%   would declare them; dc_observation/2 holds the step's observations,
%   see original_program/2).
%   Fails for any other directive.  Throws error(ddc(bad_directive(D),
%   Where), _) for an option setter with a value the original did not
%   accept.
original_directive(D, Where, Options) :-
    must_be(compound, Where),
    nonvar(D),
    conjuncts(D, Ds),
    forall(member(D1, Ds), option_setter(D1)),
    forall(member(D1, Ds), check_option(D1, Where)),
    (   memberchk(set_options(_), Ds)
    ->  Options = [first(all), facts([action/1, deltaT/1, dc_observation/2])]
    ;   Options = []
    ).

conjuncts(D, _) :- var(D), !, fail.
conjuncts((A, B), Ds) :- !,
    conjuncts(A, DA), conjuncts(B, DB), append(DA, DB, Ds).
conjuncts(D, [D]).

option_setter(D) :-
    compound(D), compound_name_arity(D, N, 1),
    memberchk(N, [set_options, set_inference, set_query_propagation, set_debug,
                  set_lifted, set_raoblackwellisation, set_current2nextcopy]).

check_option(D, Where) :-
    (   option_effect(D, Effect)
    ->  (   Effect == same
        ->  true
        ;   warned_(D, Where)           % once per directive: a filter reloads its file
        ->  true
        ;   assertz(warned_(D, Where)),
            print_message(warning, dc_compat(option_ignored(D, Effect), Where))
        )
    ;   throw(error(ddc(bad_directive(D), Where), _))
    ).

%   option_effect(+Setter, -Effect): same (this engine does it anyway) or
%   the reason the option changes nothing here.
option_effect(set_options(default), same).
option_effect(set_inference(backward(lw)), same).
option_effect(set_inference(backward(classic)), classic).
option_effect(set_inference(backward(lazy)), lazy).
option_effect(set_inference(false), forward).
option_effect(set_inference(true), forward).
option_effect(set_query_propagation(B), propagation) :- boolean(B).
option_effect(set_lifted(false), same).
option_effect(set_lifted(true), lifted).
option_effect(set_raoblackwellisation(false), same).
option_effect(set_raoblackwellisation(true), rao).
option_effect(set_debug(false), same).
option_effect(set_debug(true), debug).
option_effect(set_current2nextcopy(true), same).
option_effect(set_current2nextcopy(false), copy).

boolean(B) :- B == true ; B == false.

%!  original_program(+Items0:list, -Items:list) is det.
%
%   Items0 are the terms of a program as ddc_read.pl read them, t(Term, Line);
%   Items has the original's arithmetic rewritten in every term
%   (original_arithmetic/2) and, in a program written for the original
%   (one with a set_options/1 directive, which the original requires),
%   the original's one-entry observation weight `H ~ logfinite([W:_])`
%   (any value; its particle filter weighed by the raw log weight W)
%   rewritten to `H ~ logweight(W)` (ddc_dist.pl), whose log mass is W:
%   this engine's logfinite is normalised, so the one entry would always
%   weigh 0 in log and the observation would not count.  In such a
%   program an untimed read `observation(O) ~= V` in a clause body (the
%   original's particle filter recorded each step's observations raw in
%   the particles, so a transition could read them: tracking.pl's birth
%   of an object where it is first seen) becomes `dc_observation(O, V)`,
%   a fact of the filter step (dc_compat.pl's step_particle/5 gives one
%   for each observation), and the original's internal names of the
%   time-indexed reads, `current(h) ~= V`, `next(h) ~= V` and
%   `prior(h) ~= V` (minimalexample.pl reads `current(object(A)) ~= O`),
%   become `h:t ~= V`, `h:t+1 ~= V` and `h:0 ~= V`.
original_program(Items0, Items) :-
    must_be(list, Items0),
    maplist(original_item, Items0, Items1),
    (   member(t((:- D), _), Items1), nonvar(D),
        conjuncts(D, Ds), memberchk(set_options(_), Ds)
    ->  maplist(logweight_item, Items1, Items)
    ;   Items = Items1
    ).

original_item(t(T0, L), t(T, L)) :- !, original_arithmetic(T0, T).
original_item(I, I).

logweight_item(t(T0, L), t(T, L)) :- !, logweight_clause(T0, T).
logweight_item(I, I).

logweight_clause(T0, T) :-
    (   nonvar(T0), T0 = ':='(C0, B0)
    ->  logweight_head(C0, C),
        mapsubterms(original_read, B0, B),
        T = ':='(C, B)
    ;   logweight_head(T0, T)
    ).

logweight_head(T0, T) :-
    (   nonvar(T0), T0 = '~'(H, D), nonvar(D), D = logfinite(Ls),
        nonvar(Ls), Ls = [E], nonvar(E), E = (W:V), var(V)
    ->  T = '~'(H, logweight(W))
    ;   T = T0
    ).

original_read(R, R1) :-
    compound(R), R = '~='(X, V), nonvar(X),
    (   X = observation(O)
    ->  R1 = dc_observation(O, V)
    ;   X = current(H)
    ->  R1 = '~='(H:t, V)
    ;   X = next(H)
    ->  R1 = '~='(H:(t+1), V)
    ;   X = prior(H)
    ->  R1 = '~='(H:0, V)
    ).

%!  original_arithmetic(+Term0, -Term) is det.
%
%   Term0 with the original's (YAP's) arithmetic rewritten to SWI-Prolog's
%   inside is/2 and the arithmetic comparisons: the constant `random` (a
%   float drawn uniformly from [0,1)) becomes `random_float`.  Anything
%   else is left as it is.
original_arithmetic(T0, T) :-
    (   var(T0) ; atomic(T0) ), !,
    T = T0.
original_arithmetic(T0, T) :-
    compound_name_arguments(T0, N, As0),
    length(As0, A),
    (   arithmetic_goal(N, A)
    ->  maplist(expression, As0, As)
    ;   maplist(original_arithmetic, As0, As)
    ),
    compound_name_arguments(T, N, As).

arithmetic_goal(is, 2).
arithmetic_goal(<, 2).
arithmetic_goal(>, 2).
arithmetic_goal(=<, 2).
arithmetic_goal(>=, 2).
arithmetic_goal(=:=, 2).
arithmetic_goal(=\=, 2).

expression(E0, E) :-
    (   E0 == random
    ->  E = random_float
    ;   compound(E0)
    ->  compound_name_arguments(E0, N, As0),
        maplist(expression, As0, As),
        compound_name_arguments(E, N, As)
    ;   E = E0
    ).

:- multifile prolog:message//1.

prolog:message(dc_compat(option_ignored(D, Effect), File:Line)) -->
    [ '~w:~w: ~p: '-[File, Line, D] ],
    effect(Effect).

effect(classic) -->
    [ 'static queries always use likelihood weighting with backward reasoning here, and the filter always the classic backward proofs (the same answers within sampling error)' ].
effect(lazy) -->
    [ 'lazy inference is not implemented; static queries use likelihood weighting, the filter the classic backward proofs (the same answers within sampling error)' ].
effect(forward) -->
    [ 'forward sampling is not implemented; queries use likelihood weighting with backward reasoning (the same answers within sampling error)' ].
effect(propagation) -->
    [ 'evidence is always propagated through val/1 clauses computed by arithmetic, with the Jacobian (answers differ from the original where it left the Jacobian out)' ].
effect(lifted) -->
    [ 'lifted inference is not implemented; the answers are the ground ones' ].
effect(rao) -->
    [ 'Rao-Blackwellisation is not implemented; every variable is sampled in the particles' ].
effect(debug) -->
    [ 'debug printing of worlds is not implemented' ].
effect(copy) -->
    [ 'h:t clauses are always the fallback definition at t+1 here (there is no switch)' ].

/*  ddc_learn_worlds.pl -- proofs in partial possible worlds: a goal that
    reads an uncertain fact is proved again in each world that assigns it.
*/

:- module(ddc_learn_worlds,
          [ world_alternatives/6,       % +Data, +Goal, +Out, +World, +Factor, -Alts
            in_world/2                  % +World, :Goal
          ]).

:- use_module(library(apply)).
:- use_module(library(assoc)).
:- use_module(ddc_learn_data).

:- set_prolog_flag(optimise, true).

/** <module> Partial possible worlds

A partial world is an assoc Key-Value of the uncertain facts a proof has
read.  The data module's uncertain facts ask it through pick/3
(ddc_learn_facts.pl), which throws ddcl_need(Key, Dist) for a key the
world has not assigned; world_alternatives/6 catches it, splits the world
on the key's values (dist_points/3: a discrete distribution's support,
samples of a continuous one) and proves the goal again in each (section
4 of the paper).
*/

:- meta_predicate in_world(+, 0).

%!  world_alternatives(+Data, +Goal, +Out, +World, +Factor:float,
%!                     -Alternatives:list) is det.
%
%   The outcomes of Goal in the partial worlds that extend World, one
%   alternative(Out, World1, Factor1, Pure) each: Factor1 is Factor times
%   the probability of what World1 adds; Pure is false where the proof read
%   an uncertain fact.  Goal is proved with World as the assignment pick/3
%   reads; a pick of an unassigned key splits the world on that key's
%   values and proves again in each.  Goal is called in this module: its
%   predicates are qualified with their data module.
%
%   @error ddc_learn(too_many_worlds(Max), data) when a grounding splits
%          into more than the max_worlds option's partial worlds.
world_alternatives(M, Goal, Out, World, F, Alts) :-
    M:'$ddcl_option'(max_worlds, Max),
    M:'$ddcl_option'(samples, S),
    prove_in_worlds(Goal, Out, World, F, S, Max, 0, _, Alts, []).

prove_in_worlds(Goal, Out, World, F, S, Max, N0, N, Alts, Tail) :-
    nb_setval(ddcl_touched, false),
    copy_term(Goal-Out, G-O),
    catch(( in_world(World, G) -> R = ok(O) ; R = failed ),
          ddcl_need(K, D), R = need(K, D)),
    nb_getval(ddcl_touched, T),
    (   R = ok(O1)
    ->  ( T == true -> Pure = false ; Pure = true ),
        N is N0+1,
        (   N > Max -> throw(error(ddc_learn(too_many_worlds(Max), data), _)) ; true ),
        Alts = [alternative(O1, World, F, Pure)|Tail]
    ;   R = need(K1, D1)
    ->  dist_points(D1, S, Points),
        foldl(split_world(Goal, Out, World, F, S, Max, K1), Points, N0-Alts, N-Tail0),
        Tail0 = Tail
    ;   throw(error(ddc_learn(goal_failed(Goal), data), _))
    ).

split_world(Goal, Out, World, F, S, Max, K, P-V, N0-Alts, N-Tail) :-
    put_assoc(K, World, V, W1),
    F1 is F*P,
    prove_in_worlds(Goal, Out, W1, F1, S, Max, N0, N1, Alts0, Tail),
    mark_impure(Alts0, Tail, Alts),
    N = N1.

%   mark_impure(+Alts, +Tail, -Marked): the alternatives found in one split
%   world (Alts up to Tail) read an uncertain fact: none is pure.
mark_impure(L, Tail, L) :- L == Tail, !.
mark_impure([alternative(O, W, F, _)|T0], Tail, [alternative(O, W, F, false)|T]) :-
    mark_impure(T0, Tail, T).

%!  in_world(+World, :Goal) is semidet.
%
%   Goal with World as the partial world that pick/3 reads.
in_world(World, G) :-
    b_setval(ddcl_assign, World),
    call(G).

/*  ddc_learn_worlds.pl -- proofs in partial possible worlds: a goal that
    reads an uncertain fact is proved again in each world that assigns it.
*/

:- module(ddc_learn_worlds,
          [ alts/6,                     % +Data, +Goal, +Out, +World, +Factor, -Alts
            in_world/2                  % +World, :Goal
          ]).

:- use_module(library(apply)).
:- use_module(library(assoc)).
:- use_module(ddc_learn_data).

:- set_prolog_flag(optimise, true).

/** <module> Partial possible worlds

A partial world is an assoc Key-Value of the uncertain facts a proof has
read.  The data module's uncertain facts ask it through pick/3
(ddc_learn_data.pl), which throws ddcl_need(Key, Dist) for a key the world
has not assigned; alts/6 catches it, splits the world on the key's values
(dist_points/3: a discrete distribution's support, samples of a
continuous one) and proves the goal again in each (section 4 of the
paper).
*/

:- meta_predicate in_world(+, 0).

%   alts(+M, +Goal, +Out, +World, +F, -Alts): the outcomes of Goal in the
%   partial worlds that extend World, a(Out, World1, F1, Pure) each; F1 is
%   F times the probability of what World1 adds.  Goal is proved with
%   World as the assignment pick/3 reads; a pick of an unassigned key
%   splits the world on that key's values and proves again in each.
alts(M, Goal, Out, World, F, Alts) :-
    M:'$ddcl_option'(max_worlds, Max),
    M:'$ddcl_option'(samples, S),
    alts_(Goal, Out, World, F, S, Max, 0, _, Alts, []).

alts_(Goal, Out, World, F, S, Max, N0, N, Alts, Tail) :-
    nb_setval(ddcl_touched, false),
    copy_term(Goal-Out, G-O),
    catch(( in_world(World, G) -> R = ok(O) ; R = failed ),
          ddcl_need(K, D), R = need(K, D)),
    nb_getval(ddcl_touched, T),
    (   R = ok(O1)
    ->  ( T == true -> Pure = false ; Pure = true ),
        N is N0+1,
        (   N > Max -> throw(error(ddc_learn(too_many_worlds(Max), data), _)) ; true ),
        Alts = [a(O1, World, F, Pure)|Tail]
    ;   R = need(K1, D1)
    ->  dist_points(D1, S, Points),
        foldl(split_world(Goal, Out, World, F, S, Max, K1), Points, N0-Alts, N-Tail0),
        Tail0 = Tail
    ;   throw(error(ddc_learn(goal_failed(Goal), data), _))
    ).

split_world(Goal, Out, World, F, S, Max, K, P-V, N0-Alts, N-Tail) :-
    put_assoc(K, World, V, W1),
    F1 is F*P,
    alts_(Goal, Out, W1, F1, S, Max, N0, N1, Alts0, Tail),
    mark_impure(Alts0, Tail, Alts),
    N = N1.

mark_impure(L, Tail, L) :- L == Tail, !.
mark_impure([a(O, W, F, _)|T0], Tail, [a(O, W, F, false)|T]) :- mark_impure(T0, Tail, T).

in_world(World, G) :-
    b_setval(ddcl_assign, World),
    call(G).

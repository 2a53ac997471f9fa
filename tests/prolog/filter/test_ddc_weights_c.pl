/*  plunit: the column library's pass of the weights (col_weights_update/6) and its
    systematic resampling (col_systematic_indices/3) give what ddc_weights.pl's Prolog passes
    give, bit for bit, on random weights with -inf, NaN and +inf among them; without the
    library they fail and the Prolog passes run.
*/
:- use_module('../../../prolog/ddc/filter/ddc_weights').
:- use_module('../../../prolog/ddc/batch/ddc_batch_col').
:- use_module(library(plunit)).
:- use_module(library(apply)).

step_weight(L) :-
    R is random_float,
    (   R < 0.05 -> L is -inf ; R < 0.07 -> L is nan ; R < 0.08 -> L is inf
    ;   L is -3*random_float
    ).

prior_weight(N, L) :-
    R is random_float,
    (   R < 0.05 -> L is -inf ; L is -log(N) - random_float ).

%   prolog_passes(+LW0, +Step, -Result): weights_update/6 by its Prolog clause alone
prolog_passes(LW0, Step, LW-Inc-ESS-Inf) :-
    clause(ddc_weights:weights_update(LW0, Step, LW, Inc, ESS, Inf), Body),
    Body \= (ddc_batch_col:col_weights_update(_, _, _, _, _, _), _),
    Body \= (col_weights_update(_, _, _, _, _, _), _),
    !,
    call(ddc_weights:Body).

:- begin_tests(ddc_weights_c).

test(the_c_pass_gives_the_prolog_passes_results, [condition(col_backend(foreign))]) :-
    set_random(seed(3)),
    forall(between(1, 300, T),
           (   N is 1 + random(50),
               length(Step, N), length(LW0, N),
               NegInf is -inf,
               (   T mod 10 =:= 0 -> maplist(=(NegInf), Step) ; maplist(step_weight, Step) ),
               maplist(prior_weight(N), LW0),
               col_weights_update(LW0, Step, LW, Inc, ESS, Inf),
               prolog_passes(LW0, Step, Expected),
               assertion(LW-Inc-ESS-Inf =@= Expected)
           )).

test(the_c_systematic_resampling_picks_the_prolog_rules_indices,
     [condition(col_backend(foreign))]) :-
    set_random(seed(5)),
    forall(between(1, 300, _),
           (   N is 1 + random(60),
               length(Step, N), length(LW0, N),
               maplist(step_weight, Step), maplist(prior_weight(N), LW0),
               weights_update(LW0, Step, LW, Inc, _, _),
               (   Inc > -inf
               ->  U is random_float,
                   (   col_systematic_indices(LW, U, Is) -> true ; Is = failed ),
                   weights_normalised(LW, Ws),
                   resample_indices(systematic, Ws, [U], Expected),
                   assertion(Is == Expected)
               ;   true
               )
           )).

test(lists_of_other_lengths_are_left_to_the_prolog_passes, [condition(col_backend(foreign))]) :-
    \+ col_weights_update([-1.0, -1.0], [0.0], _, _, _, _),
    catch(weights_update([-1.0, -1.0], [0.0], _, _, _, _), E, true),
    E = error(domain_error(same_length(2), [0.0]), _).

test(without_the_library_it_fails, [condition(col_backend(prolog))]) :-
    \+ col_weights_update([0.0], [0.0], _, _, _, _).

:- end_tests(ddc_weights_c).

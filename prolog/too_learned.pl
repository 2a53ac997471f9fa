/*  too_learned.pl -- the theory of occlusion with rules learned from experience.

    Written by `anchoring learn-theory`: a tree learned (ddc learn) from
    data_truth.pl: 64040 groundings of occluder(A, O):t+1,
    50 clauses, training log-likelihood -24840.8;
    and one for released(A):t+1 from 1928 frames a hand held an object
    (3 clauses, training log-likelihood -70.2959);
    search seed 0.
    Command: anchoring learn-theory out/learn/data_truth.pl --seed 0 --out prolog/too_learned.pl --plots docs/images
    The hand-written parts are included from prolog/too/ (too_base.pl, too_learned_glue.pl, too_motion.pl):
    regenerate this file rather than edit it; edit those for the rest.  The
    parameters are fitted from the motion samples beside the data.
*/

:- include('too/too_base.pl').

% ------------------------------------------------------------------ learned parameters
% Fitted from the motion samples beside the data (python/probanchor/learning/
% motion_parameters.py: maximum-likelihood variances, least-squares AR(1) kept
% fractions, quantiles for reaches and heights, Laplace's rule for a probability);
% variances per axis in square metres, one step is one camera frame.
obs_var(2.377e-06).  % the measurement noise of a perceived position (m², per axis); 87,816 samples
motion_var(2.595e-05).  % how far a perceived object moves in a frame (m², per axis); 102,633 samples
reappear_var(0.003262).  % where a hidden object is seen again, around its belief (m²); 492 samples
lost_var(0.0664).  % the same for an object lost while the camera saw nothing (m²); 6,854 samples
follow_keep(0.9556).  % the fraction of its offset from its occluder a hidden object keeps; 12,844 samples
follow_var(3.008e-06).  % the jitter of that offset per frame (m²); 12,844 samples
coast_keep(0.9643).  % the fraction of its velocity a hidden object under nothing keeps; 27,694 samples
wander_var(1.096e-06).  % how far such an object may move besides (m²); 27,694 samples
grip_reach(0.1018).  % how far (table plane) a hand's grip may be from what it takes (m); 38 samples
grip_height(0.1281).  % how far above it (m); 38 samples
occluder_rise(0.01008).  % how far below its centre (m; negative: above); 38 samples
grip_drop(0.01771).  % how far what a hand holds is below its grip (m); 1,928 samples
grip_rise(0.00179).  % how far a hand's grip rises in a frame when it lifts (m); 538 samples

% ------------------------------------------------------------------ learned affordances
% Read from the data (python/probanchor/learning/occlusion_affordances.py): the share
% of the hidden objects a kind hides, of the pairs in which it is hidden itself,
% and of the occlusions going on in which it still holds what it hid when lifted
% off (Laplace's rule; the data points' weight in the comment).  A kind is asked
% about as an occluder when it hides at least 0.01 of them and is no
% carrier, as hidden when it is at least 0.01 of the time; a carrier holds
% what it hid when lifted off with a probability above 1/2, read from a weight of
% at least 50 data points (too/too_motion.pl's carriers' rules apply to
% it).
hides(ball, 0.0004068).  % 17,205
hides(box, 0.1117).  % 33,417
hides(can, 8.609e-05).  % 11,614
hides(cup, 0.1242).  % 31,436
hides(mug, 0.1026).  % 33,427
hides(skin, 0.5011).  % 4,744
hidden_share(ball, 0.2016).  % 50,771
hidden_share(box, 7.959e-05).  % 12,563
hidden_share(can, 0.1175).  % 24,797
hidden_share(cup, 6.934e-05).  % 14,419
hidden_share(mug, 0.03535).  % 8,429
hidden_share(skin, 4.792e-05).  % 20,864
carries(box, 0.25).  % 2
carries(cup, 0.3333).  % 1
carries(skin, 0.9916).  % 1,434
carrier(skin).
can_occlude(O) := category(O, C), hides(C, P), P >= 0.01, \+ is_carrier(O).
is_carrier(O) := category(O, C), carrier(C).
hand_known := object(O), is_carrier(O).
can_be_occluded(A) := category(A, C), hidden_share(C, P), P >= 0.01.

:- include('too/too_learned_glue.pl').
% The onset reach (m): 90% of the 58 onsets in the data were within 0.0406 m; times 2.0.
onset_reach(0.0812).

% The learned rules (ddc learn): a distributional logic tree for occluder/2 (each path from its
% root to a leaf is one clause of the tree), with the background knowledge it reads.
learned_from(own, ['data_truth.pl'],
    [occluder(_, _):t+1],
    [ type(occluder(obj, obj):t+1),
      type(pair(obj, obj):t+1),
      type(occluded_by(obj, obj):t),
      type(seen(obj):t),
      type(lost_anywhere(obj):t),
      type(distance(obj, obj):t+1),
      type(distance3(obj, obj):t+1),
      type(rise(obj, obj):t+1),
      type(lift(obj):t+1),
      type(kind(obj):t+1),
      rv(occluder(_, _):t+1, boolean),
      rv(distance(_, _):t+1, continuous),
      rv(distance3(_, _):t+1, continuous),
      rv(rise(_, _):t+1, continuous),
      rv(lift(_):t+1, continuous),
      rv(kind(_):t+1, discrete([ball, box, can, cup, mug, skin])),
      examples(occluder(A, B):t+1, pair(A, B):t+1)]).

% Background knowledge from the data that the learned clauses call.
distance(A, O):t+1 ~ val(D) :=
    pos(A):t ~= (X, Y, _),
    pos(O):t+1 ~= (XO, YO, _),
    D is sqrt((X-XO)**2+(Y-YO)**2).
rise(A, O):t+1 ~ val(H) :=
    pos(A):t ~= (_, _, Z),
    pos(O):t+1 ~= (_, _, ZO),
    H is ZO-Z.
lift(O):t+1 ~ val(H) :=
    pos(O):t ~= (_, _, Z0),
    pos(O):t+1 ~= (_, _, Z1),
    H is Z1-Z0.
kind(A):t+1 ~ val(C) :=
    category(A, C).

% occluder(Occluded, Occluder):t+1: 50 clauses, 64040 groundings, training log-likelihood -24840.8 (mean -0.13641 per grounding), 86 parameters.
occluder(Occluded, Occluder):t+1 ~ finite([P1:true, P2:false]) :=
    pair(Occluded, Occluder):t+1,
    (   distance(Occluded, Occluder):t+1 ~= Distance
    ->  (   occluded_by(Occluded, Occluder):t
        ->  (   lift(Occluder):t+1 ~= Lift
            ->  % n = 4840 (weight 13424), log-likelihood -455.478, logistic
                logistic([Distance, Lift], [10.1981, -134.36, 5.45625], P1),
                P2 is 1-P1
            ;   % n = 0, too few groundings for a model of its own: the parent's model, finite
                P1 = 0.99083867,
                P2 = 0.00916133
            )
        ;   (   kind(Occluded):t+1 ~= ball
            ->  (   kind(Occluder):t+1 ~= ball
                ->  % n = 2135 (weight 7411), log-likelihood -0.999798, finite
                    P1 = 0.000134898,
                    P2 = 0.999865102
                ;   kind(Occluder):t+1 ~= box
                ->  (   rise(Occluded, Occluder):t+1 ~= Rise
                    ->  (   Rise < 0.0
                        ->  % n = 0, too few groundings for a model of its own: the parent's model, logistic
                            logistic([Distance], [-13.3431, 0.194924], P1),
                            P2 is 1-P1
                        ;   Rise < 0.1
                        ->  (   seen(Occluded):t
                            ->  % n = 114, log-likelihood -0.987019, finite
                                P1 = 0.00862069,
                                P2 = 0.99137931
                            ;   (   lost_anywhere(Occluded):t
                                ->  % n = 55 (weight 247), log-likelihood -1.24872, logistic
                                    logistic([Distance], [-39.9308, 3.90535], P1),
                                    P2 is 1-P1
                                ;   % n = 7061 (weight 20789), log-likelihood -4584, logistic
                                    logistic([Distance], [-13.2081, 0.224528], P1),
                                    P2 is 1-P1
                                )
                            )
                        ;   (   lift(Occluder):t+1 ~= Lift2
                            ->  % n = 519 (weight 719), log-likelihood -85.7047, logistic
                                logistic([Distance, Lift2], [-22.6107, -40.7645, -0.158582], P1),
                                P2 is 1-P1
                            ;   % n = 0, too few groundings for a model of its own: the parent's model, logistic
                                logistic([Distance], [-19.3652, -0.480469], P1),
                                P2 is 1-P1
                            )
                        )
                    ;   % n = 0, too few groundings for a model of its own: the parent's model, logistic
                        logistic([Distance], [-13.3431, 0.194924], P1),
                        P2 is 1-P1
                    )
                ;   kind(Occluder):t+1 ~= can
                ->  % n = 1738 (weight 7054), log-likelihood -0.999787, finite
                    P1 = 0.000141723,
                    P2 = 0.999858277
                ;   kind(Occluder):t+1 ~= cup
                ->  (   lost_anywhere(Occluded):t
                    ->  (   seen(Occluder):t
                        ->  % n = 50 (weight 242), log-likelihood -0.993841, finite
                            P1 = 0.00409836,
                            P2 = 0.99590164
                        ;   % n = 13 (weight 25), log-likelihood -13.8015, finite
                            P1 = 0.259259,
                            P2 = 0.740741
                        )
                    ;   (   rise(Occluded, Occluder):t+1 ~= Rise4
                        ->  (   Rise4 < 0.0
                            ->  % n = 369 (weight 929), log-likelihood -352.666, logistic
                                logistic([Distance], [-11.3695, 0.821599], P1),
                                P2 is 1-P1
                            ;   Rise4 < 0.1
                            ->  (   seen(Occluded):t
                                ->  % n = 90, log-likelihood -4.14141, logistic
                                    logistic([Distance], [-33.8381, 2.49258], P1),
                                    P2 is 1-P1
                                ;   % n = 7206 (weight 18654), log-likelihood -7876.12, logistic
                                    logistic([Distance], [-5.25176, -0.418674], P1),
                                    P2 is 1-P1
                                )
                            ;   % n = 438 (weight 522), log-likelihood -97.6927, logistic
                                logistic([Distance], [-12.2049, -0.430327], P1),
                                P2 is 1-P1
                            )
                        ;   % n = 0, too few groundings for a model of its own: the parent's model, logistic
                            logistic([Distance], [-5.50569, -0.388962], P1),
                            P2 is 1-P1
                        )
                    )
                ;   kind(Occluder):t+1 ~= mug
                ->  (   rise(Occluded, Occluder):t+1 ~= Rise8
                    ->  (   Rise8 < 0.0
                        ->  % n = 220 (weight 780), log-likelihood -6.50984, logistic
                            logistic([Distance], [27.627, -16.2347], P1),
                            P2 is 1-P1
                        ;   Rise8 < 0.1
                        ->  (   lost_anywhere(Occluded):t
                            ->  % n = 114 (weight 354), log-likelihood -4.90048, logistic
                                logistic([Distance], [-28.8458, 1.91844], P1),
                                P2 is 1-P1
                            ;   (   seen(Occluded):t
                                ->  % n = 93, log-likelihood -7.52216, logistic
                                    logistic([Distance], [-27.187, 2.06956], P1),
                                    P2 is 1-P1
                                ;   % n = 7287 (weight 17955), log-likelihood -7155.36, logistic
                                    logistic([Distance], [-7.92665, 0.212344], P1),
                                    P2 is 1-P1
                                )
                            )
                        ;   % n = 341 (weight 409), log-likelihood -42.6772, logistic
                            logistic([Distance], [-15.4052, -0.419447], P1),
                            P2 is 1-P1
                        )
                    ;   % n = 0, too few groundings for a model of its own: the parent's model, logistic
                        logistic([Distance], [-8.31822, 0.207997], P1),
                        P2 is 1-P1
                    )
                ;   kind(Occluder):t+1 ~= skin
                ->  % n = 2122 (weight 2486), log-likelihood -1258.82, logistic
                    logistic([Distance], [-7.19555, 0.738381], P1),
                    P2 is 1-P1
                ;   \+ kind(Occluder):t+1 ~= _
                ->  % n = 0, too few groundings for a model of its own: the parent's model, logistic
                    logistic([Distance], [-8.82591, -0.104788], P1),
                    P2 is 1-P1
                )
            ;   kind(Occluded):t+1 ~= box
            ->  % n = 4275 (weight 12563), log-likelihood -0.999881, finite
                P1 = 7.95862e-5,
                P2 = 0.9999204138
            ;   kind(Occluded):t+1 ~= can
            ->  (   kind(Occluder):t+1 ~= ball
                ->  (   seen(Occluder):t
                    ->  % n = 1056 (weight 4516), log-likelihood -0.999668, finite
                        P1 = 0.000221337,
                        P2 = 0.999778663
                    ;   (   lift(Occluder):t+1 ~= Lift4
                        ->  % n = 54 (weight 74), log-likelihood -20.6741, logistic
                            logistic([Distance, Lift4], [-6.95313, 43.8021, -0.726311], P1),
                            P2 is 1-P1
                        ;   % n = 0, too few groundings for a model of its own: the parent's model, finite
                            P1 = 0.171053,
                            P2 = 0.828947
                        )
                    )
                ;   kind(Occluder):t+1 ~= box
                ->  (   rise(Occluded, Occluder):t+1 ~= Rise12
                    ->  (   Rise12 < 0.0
                        ->  % n = 472 (weight 960), log-likelihood -26.4003, logistic
                            logistic([Distance], [-55.6646, 4.23831], P1),
                            P2 is 1-P1
                        ;   Rise12 < 0.1
                        ->  (   lost_anywhere(Occluded):t
                            ->  % n = 63 (weight 159), log-likelihood -12.0234, logistic
                                logistic([Distance], [-19.6305, 0.509502], P1),
                                P2 is 1-P1
                            ;   % n = 2202 (weight 5210), log-likelihood -2124.26, logistic
                                logistic([Distance], [-9.45809, 0.707409], P1),
                                P2 is 1-P1
                            )
                        ;   % n = 406 (weight 498), log-likelihood -49.023, finite
                            P1 = 0.022,
                            P2 = 0.978
                        )
                    ;   % n = 0, too few groundings for a model of its own: the parent's model, logistic
                        logistic([Distance], [-11.9366, 1.05152], P1),
                        P2 is 1-P1
                    )
                ;   kind(Occluder):t+1 ~= can
                ->  % n = 628 (weight 2804), log-likelihood -0.999465, finite
                    P1 = 0.000356379,
                    P2 = 0.999643621
                ;   kind(Occluder):t+1 ~= cup
                ->  % n = 2277 (weight 8305), log-likelihood -0.999819, finite
                    P1 = 0.00012038,
                    P2 = 0.99987962
                ;   kind(Occluder):t+1 ~= mug
                ->  % n = 2379 (weight 8323), log-likelihood -0.99982, finite
                    P1 = 0.00012012,
                    P2 = 0.99987988
                ;   kind(Occluder):t+1 ~= skin
                ->  (   lift(Occluder):t+1 ~= Lift6
                    ->  (   rise(Occluded, Occluder):t+1 ~= Rise16
                        ->  (   Rise16 < 0.0
                            ->  % n = 33 (weight 37), log-likelihood -0.961093, finite
                                P1 = 0.025641,
                                P2 = 0.974359
                            ;   Rise16 < 0.1
                            ->  % n = 418, log-likelihood -144.281, logistic
                                logistic([Distance, Lift6], [-5.55309, -40.538, 3.0097], P1),
                                P2 is 1-P1
                            ;   (   lost_anywhere(Occluded):t
                                ->  % n = 33 (weight 37), log-likelihood -12.7441, finite
                                    P1 = 0.128205,
                                    P2 = 0.871795
                                ;   % n = 1321 (weight 1337), log-likelihood -453.602, logistic
                                    logistic([Distance, Lift6], [-7.97585, -60.1664, 3.53919], P1),
                                    P2 is 1-P1
                                )
                            )
                        ;   % n = 0, too few groundings for a model of its own: the parent's model, logistic
                            logistic([Distance, Lift6], [-7.09987, -45.4514, 3.07544], P1),
                            P2 is 1-P1
                        )
                    ;   % n = 0, too few groundings for a model of its own: the parent's model, logistic
                        logistic([Distance], [-6.34233, 2.78286], P1),
                        P2 is 1-P1
                    )
                ;   \+ kind(Occluder):t+1 ~= _
                ->  % n = 0, too few groundings for a model of its own: the parent's model, logistic
                    logistic([Distance], [-12.5838, 0.256381], P1),
                    P2 is 1-P1
                )
            ;   kind(Occluded):t+1 ~= cup
            ->  % n = 4439 (weight 14419), log-likelihood -0.999896, finite
                P1 = 6.93433e-5,
                P2 = 0.9999306567
            ;   kind(Occluded):t+1 ~= mug
            ->  % n = 3231 (weight 9283), log-likelihood -39.2145, logistic
                logistic([Distance], [-206.746, 4.40099], P1),
                P2 is 1-P1
            ;   kind(Occluded):t+1 ~= skin
            ->  % n = 5948 (weight 20864), log-likelihood -0.999928, finite
                P1 = 4.79249e-5,
                P2 = 0.9999520751
            ;   \+ kind(Occluded):t+1 ~= _
            ->  % n = 0, too few groundings for a model of its own: the parent's model, logistic
                logistic([Distance], [-10.2246, -0.36136], P1),
                P2 is 1-P1
            )
        )
    ;   % n = 0, too few groundings for a model of its own: the parent's model, finite
        P1 = 0.144751,
        P2 = 0.855249
    ).

% When a hand lets go of what it carries (ddc learn, from the carries beside the data): a
% distributional logic tree for released/1, with the background knowledge it reads.
learned_from(own, ['data_truth.release.pl'],
    [released(_):t+1],
    [ type(released(obj):t+1),
      type(carried(obj):t+1),
      type(height(obj):t+1),
      type(highest(obj):t+1),
      rv(released(_):t+1, boolean),
      rv(height(_):t+1, continuous),
      rv(highest(_):t+1, continuous),
      examples(released(A):t+1, carried(A):t+1)]).

% Background knowledge from the data that the learned clauses call.
height(A):t+1 ~ val(H) :=
    pos(A):t ~= (_, _, Z),
    rest_z(A):t ~= R,
    H is Z-R.
highest(A):t+1 ~ val(H) :=
    top(A):t ~= H.

% released(Held):t+1: 3 clauses, 1928 groundings, training log-likelihood -70.2959 (mean -0.0364605 per grounding), 6 parameters.
released(Held):t+1 ~ finite([P1:true, P2:false]) :=
    carried(Held):t+1,
    (   height(Held):t+1 ~= Height
    ->  (   highest(Held):t+1 ~= Highest
        ->  % n = 1928, log-likelihood -70.2959, logistic
            logistic([Height, Highest], [-90.9747, 32.2868, -4.7466], P1),
            P2 is 1-P1
        ;   % n = 0, too few groundings for a model of its own: the parent's model, logistic
            logistic([Height], [-74.8804, -1.1015], P1),
            P2 is 1-P1
        )
    ;   % n = 0, too few groundings for a model of its own: the parent's model, finite
        P1 = 0.0243523,
        P2 = 0.9756477
    ).

:- include('too/too_motion.pl').

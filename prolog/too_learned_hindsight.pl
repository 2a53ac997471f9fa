/*  too_learned_hindsight.pl -- the theory of occlusion with rules learned from experience.

    Written by `anchoring learn-theory`: a tree learned (ddc learn) from
    data_hindsight.pl: 54578 groundings of occluder(A, O):t+1,
    69 clauses, training log-likelihood -14080.6;
    and one for released(A):t+1 from 1430 frames a hand held an object
    (3 clauses, training log-likelihood -36.672);
    search seed 0.
    Command: anchoring learn-theory out/learn/data_hindsight.pl --seed 0 --out prolog/too_learned_hindsight.pl --plots docs/images
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
obs_var(3.976e-06).  % the measurement noise of a perceived position (m², per axis); 104,905 samples
motion_var(2.969e-05).  % how far a perceived object moves in a frame (m², per axis); 138,538 samples
reappear_var(0.001087).  % where a hidden object is seen again, around its belief (m²); 1,403 samples
lost_var(0.07437).  % the same for an object lost while the camera saw nothing (m²); 9,313 samples
follow_keep(0.9976).  % the fraction of its offset from its occluder a hidden object keeps; 37 samples
follow_var(1e-08).  % the jitter of that offset per frame (m²); 37 samples
coast_keep(0.8164).  % the fraction of its velocity a hidden object under nothing keeps; 36 samples
wander_var(0.0004746).  % how far such an object may move besides (m²); 36 samples
grip_reach(0.06652).  % how far (table plane) a hand's grip may be from what it takes (m); 23 samples
grip_height(0.1211).  % how far above it (m); 23 samples
occluder_rise(0.003004).  % how far below its centre (m); 23 samples
grip_drop(0.04053).  % how far what a hand holds is below its grip (m); 23 samples
grip_rise(0.001603).  % how far a hand's grip rises in a frame when it lifts (m); 292 samples

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
hides(ball, 9.58e-05).  % 10,436
hides(box, 0.1231).  % 23,895
hides(can, 0.0001061).  % 9,423
hides(cup, 0.2084).  % 26,669
hides(mug, 0.1238).  % 21,741
hides(skin, 0.2838).  % 4,315
hidden_share(ball, 0.2278).  % 44,154
hidden_share(box, 0.02132).  % 7,222
hidden_share(can, 0.3207).  % 2,995
hidden_share(cup, 0.01228).  % 20,931
hidden_share(mug, 0.07262).  % 13,603
hidden_share(skin, 0.000132).  % 7,574
carries(box, 0.75).  % 2
carries(skin, 0.9986).  % 700
carrier(skin).
can_occlude(O) := category(O, C), hides(C, P), P >= 0.01, \+ is_carrier(O).
is_carrier(O) := category(O, C), carrier(C).
hand_known := object(O), is_carrier(O).
can_be_occluded(A) := category(A, C), hidden_share(C, P), P >= 0.01.

:- include('too/too_learned_glue.pl').
% The onset reach (m): 90% of the 56 onsets in the data were within 0.05456 m; times 2.0.
onset_reach(0.1091).

% The learned rules (ddc learn): a distributional logic tree for occluder/2 (each path from its
% root to a leaf is one clause of the tree), with the background knowledge it reads.
learned_from(own, ['data_hindsight.pl'],
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

% occluder(Occluded, Occluder):t+1: 69 clauses, 54578 groundings, training log-likelihood -14080.6 (mean -0.0995332 per grounding), 102 parameters.
occluder(Occluded, Occluder):t+1 ~ finite([P1:true, P2:false]) :=
    pair(Occluded, Occluder):t+1,
    (   distance(Occluded, Occluder):t+1 ~= Distance
    ->  (   kind(Occluded):t+1 ~= ball
        ->  (   kind(Occluder):t+1 ~= ball
            ->  % n = 1062 (weight 3290), log-likelihood -0.999544, finite
                P1 = 0.000303767,
                P2 = 0.999696233
            ;   kind(Occluder):t+1 ~= box
            ->  (   occluded_by(Occluded, Occluder):t
                ->  % n = 408 (weight 1348), log-likelihood -0.998889, finite
                    P1 = 0.999259259,
                    P2 = 0.000740741
                ;   (   lost_anywhere(Occluded):t
                    ->  % n = 107 (weight 283), log-likelihood -12.0813, finite
                        P1 = 0.0105263,
                        P2 = 0.9894737
                    ;   % n = 6975 (weight 19707), log-likelihood -1738.66, logistic
                        logistic([Distance], [-34.5664, 1.19425], P1),
                        P2 is 1-P1
                    )
                )
            ;   kind(Occluder):t+1 ~= can
            ->  % n = 2302 (weight 9058), log-likelihood -0.999834, finite
                P1 = 0.000110375,
                P2 = 0.999889625
            ;   kind(Occluder):t+1 ~= cup
            ->  (   occluded_by(Occluded, Occluder):t
                ->  % n = 1572 (weight 5520), log-likelihood -0.999728, finite
                    P1 = 0.999818906,
                    P2 = 0.000181094
                ;   (   seen(Occluder):t
                    ->  (   rise(Occluded, Occluder):t+1 ~= Rise
                        ->  (   Rise < 0.0
                            ->  % n = 83 (weight 207), log-likelihood -6.62997, finite
                                P1 = 0.00956938,
                                P2 = 0.99043062
                            ;   Rise < 0.1
                            ->  (   seen(Occluded):t
                                ->  % n = 96, log-likelihood -7.05843, logistic
                                    logistic([Distance], [-30.0452, 2.1561], P1),
                                    P2 is 1-P1
                                ;   % n = 8676 (weight 16800), log-likelihood -6281.21, logistic
                                    logistic([Distance], [-12.2361, 1.57498], P1),
                                    P2 is 1-P1
                                )
                            ;   (   lift(Occluder):t+1 ~= Lift
                                ->  % n = 165 (weight 185), log-likelihood -51.4232, logistic
                                    logistic([Distance, Lift], [-16.1364, 113.373, 0.940312], P1),
                                    P2 is 1-P1
                                ;   % n = 0, too few groundings for a model of its own: the parent's model, logistic
                                    logistic([Distance], [-10.8477, 0.891046], P1),
                                    P2 is 1-P1
                                )
                            )
                        ;   % n = 0, too few groundings for a model of its own: the parent's model, logistic
                            logistic([Distance], [-12.2802, 1.54793], P1),
                            P2 is 1-P1
                        )
                    ;   (   rise(Occluded, Occluder):t+1 ~= Rise4
                        ->  (   Rise4 < 0.0
                            ->  % n = 10 (weight 14), log-likelihood -3.81535, finite
                                P1 = 0.125,
                                P2 = 0.875
                            ;   Rise4 < 0.1
                            ->  % n = 243 (weight 671), log-likelihood -76.6974, logistic
                                logistic([Distance], [-18.057, 0.193258], P1),
                                P2 is 1-P1
                            ;   % n = 0, too few groundings for a model of its own: the parent's model, logistic
                                logistic([Distance], [-15.505, -0.131799], P1),
                                P2 is 1-P1
                            )
                        ;   % n = 0, too few groundings for a model of its own: the parent's model, logistic
                            logistic([Distance], [-15.505, -0.131799], P1),
                            P2 is 1-P1
                        )
                    )
                )
            ;   kind(Occluder):t+1 ~= mug
            ->  (   occluded_by(Occluded, Occluder):t
                ->  % n = 703 (weight 2675), log-likelihood -0.99944, finite
                    P1 = 0.999626448,
                    P2 = 0.000373552
                ;   (   rise(Occluded, Occluder):t+1 ~= Rise8
                    ->  (   Rise8 < 0.0
                        ->  % n = 179 (weight 291), log-likelihood -3.46333, logistic
                            logistic([Distance], [-44.2361, 5.89902], P1),
                            P2 is 1-P1
                        ;   Rise8 < 0.1
                        ->  % n = 6853 (weight 17805), log-likelihood -2659.28, logistic
                            logistic([Distance], [-26.0509, 2.08665], P1),
                            P2 is 1-P1
                        ;   % n = 111 (weight 127), log-likelihood -9.19703, logistic
                            logistic([Distance], [-14.8309, -0.709224], P1),
                            P2 is 1-P1
                        )
                    ;   % n = 0, too few groundings for a model of its own: the parent's model, logistic
                        logistic([Distance], [-26.3069, 2.1227], P1),
                        P2 is 1-P1
                    )
                )
            ;   kind(Occluder):t+1 ~= skin
            ->  (   occluded_by(Occluded, Occluder):t
                ->  % n = 356 (weight 448), log-likelihood -0.996663, finite
                    P1 = 0.99777778,
                    P2 = 0.00222222
                ;   % n = 2848 (weight 3500), log-likelihood -1209.24, logistic
                    logistic([Distance], [-8.53903, 0.149388], P1),
                    P2 is 1-P1
                )
            ;   \+ kind(Occluder):t+1 ~= _
            ->  % n = 0, too few groundings for a model of its own: the parent's model, logistic
                logistic([Distance], [-21.0509, 1.98128], P1),
                P2 is 1-P1
            )
        ;   kind(Occluded):t+1 ~= box
        ->  (   kind(Occluder):t+1 ~= ball
            ->  % n = 618 (weight 1838), log-likelihood -9.00407, logistic
                logistic([Distance], [-17.584, -2.10129], P1),
                P2 is 1-P1
            ;   kind(Occluder):t+1 ~= box
            ->  (   rise(Occluded, Occluder):t+1 ~= Rise12
                ->  (   Rise12 < 0.0
                    ->  % n = 105 (weight 181), log-likelihood -13.4905, logistic
                        logistic([Distance], [-81.8139, 7.46584], P1),
                        P2 is 1-P1
                    ;   Rise12 < 0.1
                    ->  % n = 286 (weight 1018), log-likelihood -23.5648, logistic
                        logistic([Distance], [-20.6632, -1.27042], P1),
                        P2 is 1-P1
                    ;   % n = 15, log-likelihood -0.909369, finite
                        P1 = 0.0588235,
                        P2 = 0.9411765
                    )
                ;   % n = 0, too few groundings for a model of its own: the parent's model, logistic
                    logistic([Distance], [-41.0033, 2.06418], P1),
                    P2 is 1-P1
                )
            ;   kind(Occluder):t+1 ~= can
            ->  % n = 154 (weight 526), log-likelihood -0.997157, finite
                P1 = 0.00189394,
                P2 = 0.99810606
            ;   kind(Occluder):t+1 ~= cup
            ->  % n = 895 (weight 2363), log-likelihood -46.9777, logistic
                logistic([Distance], [-37.533, 0.682376], P1),
                P2 is 1-P1
            ;   kind(Occluder):t+1 ~= mug
            ->  % n = 827 (weight 2523), log-likelihood -16.4678, finite
                P1 = 0.00118812,
                P2 = 0.99881188
            ;   kind(Occluder):t+1 ~= skin
            ->  (   occluded_by(Occluded, Occluder):t
                ->  % n = 83 (weight 99), log-likelihood -0.985083, finite
                    P1 = 0.99009901,
                    P2 = 0.00990099
                ;   (   seen(Occluded):t
                    ->  % n = 48, log-likelihood -5.13751, finite
                        P1 = 0.04,
                        P2 = 0.96
                    ;   % n = 229 (weight 253), log-likelihood -173.923, finite
                        P1 = 0.447059,
                        P2 = 0.552941
                    )
                )
            ;   \+ kind(Occluder):t+1 ~= _
            ->  % n = 0, too few groundings for a model of its own: the parent's model, logistic
                logistic([Distance], [-20.1836, 0.441841], P1),
                P2 is 1-P1
            )
        ;   kind(Occluded):t+1 ~= can
        ->  (   rise(Occluded, Occluder):t+1 ~= Rise16
            ->  (   Rise16 < 0.0
                ->  % n = 376 (weight 1152), log-likelihood -0.9987, finite
                    P1 = 0.000866551,
                    P2 = 0.999133449
                ;   Rise16 < 0.1
                ->  % n = 1219 (weight 2699), log-likelihood -48.2173, logistic
                    logistic([Distance], [-131.022, 5.55773], P1),
                    P2 is 1-P1
                ;   % n = 280 (weight 332), log-likelihood -7.91406, logistic
                    logistic([Distance], [-35.11, 1.14344], P1),
                    P2 is 1-P1
                )
            ;   % n = 0, too few groundings for a model of its own: the parent's model, logistic
                logistic([Distance], [-133.405, 5.00441], P1),
                P2 is 1-P1
            )
        ;   kind(Occluded):t+1 ~= cup
        ->  (   kind(Occluder):t+1 ~= ball
            ->  % n = 1245 (weight 3933), log-likelihood -0.999619, finite
                P1 = 0.00025413,
                P2 = 0.99974587
            ;   kind(Occluder):t+1 ~= box
            ->  (   rise(Occluded, Occluder):t+1 ~= Rise20
                ->  (   Rise20 < 0.0
                    ->  % n = 98 (weight 190), log-likelihood -0.992169, finite
                        P1 = 0.00520833,
                        P2 = 0.99479167
                    ;   Rise20 < 0.1
                    ->  (   occluded_by(Occluded, Occluder):t
                        ->  % n = 47 (weight 167), log-likelihood -0.991101, finite
                            P1 = 0.99408284,
                            P2 = 0.00591716
                        ;   % n = 1407 (weight 4219), log-likelihood -142.666, logistic
                            logistic([Distance], [-67.5021, 2.34745], P1),
                            P2 is 1-P1
                        )
                    ;   % n = 109 (weight 153), log-likelihood -0.990295, finite
                        P1 = 0.00645161,
                        P2 = 0.99354839
                    )
                ;   % n = 0, too few groundings for a model of its own: the parent's model, logistic
                    logistic([Distance], [-96.0975, 2.9286], P1),
                    P2 is 1-P1
                )
            ;   kind(Occluder):t+1 ~= can
            ->  % n = 842 (weight 2110), log-likelihood -0.99929, finite
                P1 = 0.000473485,
                P2 = 0.999526515
            ;   kind(Occluder):t+1 ~= cup
            ->  % n = 2187 (weight 5459), log-likelihood -0.999725, finite
                P1 = 0.000183117,
                P2 = 0.999816883
            ;   kind(Occluder):t+1 ~= mug
            ->  % n = 1919 (weight 5087), log-likelihood -0.999705, finite
                P1 = 0.000196502,
                P2 = 0.999803498
            ;   kind(Occluder):t+1 ~= skin
            ->  (   occluded_by(Occluded, Occluder):t
                ->  % n = 64 (weight 84), log-likelihood -0.982467, finite
                    P1 = 0.9883721,
                    P2 = 0.0116279
                ;   % n = 470 (weight 578), log-likelihood -246.338, logistic
                    logistic([Distance], [-2.94134, -1.16625], P1),
                    P2 is 1-P1
                )
            ;   \+ kind(Occluder):t+1 ~= _
            ->  % n = 0, too few groundings for a model of its own: the parent's model, logistic
                logistic([Distance], [-19.5709, -1.49274], P1),
                P2 is 1-P1
            )
        ;   kind(Occluded):t+1 ~= mug
        ->  (   kind(Occluder):t+1 ~= ball
            ->  % n = 716 (weight 2312), log-likelihood -0.999352, finite
                P1 = 0.000432152,
                P2 = 0.999567848
            ;   kind(Occluder):t+1 ~= box
            ->  (   occluded_by(Occluded, Occluder):t
                ->  % n = 103 (weight 403), log-likelihood -0.996292, finite
                    P1 = 0.99753086,
                    P2 = 0.00246914
                ;   (   lost_anywhere(Occluded):t
                    ->  % n = 70 (weight 290), log-likelihood -6.96987, finite
                        P1 = 0.00684932,
                        P2 = 0.99315068
                    ;   (   rise(Occluded, Occluder):t+1 ~= Rise24
                        ->  (   Rise24 < 0.0
                            ->  % n = 103 (weight 267), log-likelihood -0.994415, finite
                                P1 = 0.00371747,
                                P2 = 0.99628253
                            ;   Rise24 < 0.1
                            ->  % n = 1205 (weight 3125), log-likelihood -451.817, logistic
                                logistic([Distance], [-33.7046, 1.17749], P1),
                                P2 is 1-P1
                            ;   % n = 111 (weight 167), log-likelihood -6.41297, finite
                                P1 = 0.0118343,
                                P2 = 0.9881657
                            )
                        ;   % n = 0, too few groundings for a model of its own: the parent's model, logistic
                            logistic([Distance], [-35.5421, 1.00591], P1),
                            P2 is 1-P1
                        )
                    )
                )
            ;   kind(Occluder):t+1 ~= can
            ->  % n = 455 (weight 1731), log-likelihood -0.999134, finite
                P1 = 0.000577034,
                P2 = 0.999422966
            ;   kind(Occluder):t+1 ~= cup
            ->  % n = 1357 (weight 4993), log-likelihood -0.9997, finite
                P1 = 0.0002002,
                P2 = 0.9997998
            ;   kind(Occluder):t+1 ~= mug
            ->  % n = 537 (weight 1677), log-likelihood -0.999106, finite
                P1 = 0.000595593,
                P2 = 0.999404407
            ;   kind(Occluder):t+1 ~= skin
            ->  (   occluded_by(Occluded, Occluder):t
                ->  % n = 412 (weight 568), log-likelihood -0.997366, finite
                    P1 = 0.99824561,
                    P2 = 0.00175439
                ;   (   seen(Occluded):t
                    ->  % n = 57, log-likelihood -9.7838, logistic
                        logistic([Distance], [-25.842, 1.79321], P1),
                        P2 is 1-P1
                    ;   % n = 1066 (weight 1250), log-likelihood -787.295, logistic
                        logistic([Distance], [-4.56221, 0.728141], P1),
                        P2 is 1-P1
                    )
                )
            ;   \+ kind(Occluder):t+1 ~= _
            ->  % n = 0, too few groundings for a model of its own: the parent's model, logistic
                logistic([Distance], [-18.2077, 0.767794], P1),
                P2 is 1-P1
            )
        ;   kind(Occluded):t+1 ~= skin
        ->  % n = 2114 (weight 7574), log-likelihood -0.999802, finite
            P1 = 0.000131996,
            P2 = 0.999868004
        ;   \+ kind(Occluded):t+1 ~= _
        ->  % n = 0, too few groundings for a model of its own: the parent's model, logistic
            logistic([Distance], [-20.273, 1.30581], P1),
            P2 is 1-P1
        )
    ;   % n = 0, too few groundings for a model of its own: the parent's model, finite
        P1 = 0.172576,
        P2 = 0.827424
    ).

% When a hand lets go of what it carries (ddc learn, from the carries beside the data): a
% distributional logic tree for released/1, with the background knowledge it reads.
learned_from(own, ['data_hindsight.release.pl'],
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

% released(Held):t+1: 3 clauses, 1430 groundings, training log-likelihood -36.672 (mean -0.0256448 per grounding), 6 parameters.
released(Held):t+1 ~ finite([P1:true, P2:false]) :=
    carried(Held):t+1,
    (   height(Held):t+1 ~= Height
    ->  (   highest(Held):t+1 ~= Highest
        ->  % n = 1430, log-likelihood -36.672, logistic
            logistic([Height, Highest], [-92.6335, 32.7764, -5.53463], P1),
            P2 is 1-P1
        ;   % n = 0, too few groundings for a model of its own: the parent's model, logistic
            logistic([Height], [-55.1553, -1.93857], P1),
            P2 is 1-P1
        )
    ;   % n = 0, too few groundings for a model of its own: the parent's model, finite
        P1 = 0.0167598,
        P2 = 0.9832402
    ).

:- include('too/too_motion.pl').

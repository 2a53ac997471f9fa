/*  too_learned_hindsight.pl -- the theory of occlusion with rules learned from experience.

    Written by `anchoring learn-theory`: a tree learned (ddc learn) from
    data_hindsight.pl: 25909 groundings of occluder(A, O):t+1,
    29 clauses, training log-likelihood -9173.66;
    and one for released(A):t+1 from 1928 frames a hand held an object
    (3 clauses, training log-likelihood -70.2959);
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
obs_var(2.377e-06).  % the measurement noise of a perceived position (m², per axis); 87,816 samples
motion_var(2.595e-05).  % how far a perceived object moves in a frame (m², per axis); 102,633 samples
reappear_var(0.003261).  % where a hidden object is seen again, around its belief (m²); 492 samples
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
hides(ball, 0.001136).  % 3,520
hides(box, 0.1805).  % 12,513
hides(can, 0.0002791).  % 3,581
hides(cup, 0.2209).  % 10,197
hides(mug, 0.2581).  % 10,271
hides(skin, 0.09828).  % 1,514
hidden_share(ball, 0.2162).  % 29,921
hidden_share(box, 0.002656).  % 2,634
hidden_share(can, 0.1765).  % 2,689
hidden_share(cup, 0.01036).  % 1,832
hidden_share(mug, 0.1042).  % 3,328
hidden_share(skin, 0.0008375).  % 1,192
carries(box, 0.9744).  % 37
carries(skin, 0.9851).  % 65
carrier(skin).
can_occlude(O) := category(O, C), hides(C, P), P >= 0.01, \+ is_carrier(O).
is_carrier(O) := category(O, C), carrier(C).
hand_known := object(O), is_carrier(O).
can_be_occluded(A) := category(A, C), hidden_share(C, P), P >= 0.01.

:- include('too/too_learned_glue.pl').
% The onset reach (m): 90% of the 66 onsets in the data were within 0.05346 m; times 2.0.
onset_reach(0.1069).

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
kind(A):t+1 ~ val(C) :=
    category(A, C).

% occluder(Occluded, Occluder):t+1: 29 clauses, 25909 groundings, training log-likelihood -9173.66 (mean -0.134984 per grounding), 47 parameters.
occluder(Occluded, Occluder):t+1 ~ finite([P1:true, P2:false]) :=
    pair(Occluded, Occluder):t+1,
    (   distance(Occluded, Occluder):t+1 ~= Distance
    ->  (   occluded_by(Occluded, Occluder):t
        ->  % n = 2127 (weight 7219), log-likelihood -0.999792, finite
            P1 = 0.999861515,
            P2 = 0.000138485
        ;   (   kind(Occluded):t+1 ~= ball
            ->  (   kind(Occluder):t+1 ~= ball
                ->  (   rise(Occluded, Occluder):t+1 ~= Rise
                    ->  (   Rise < 0.0
                        ->  % n = 548 (weight 1944), log-likelihood -0.999229, finite
                            P1 = 0.000513875,
                            P2 = 0.999486125
                        ;   Rise < 0.1
                        ->  % n = 435 (weight 1475), log-likelihood -3.77719, logistic
                            logistic([Distance], [-46.4231, 2.40628], P1),
                            P2 is 1-P1
                        ;   % n = 0, too few groundings for a model of its own: the parent's model, logistic
                            logistic([Distance], [-36.505, 0.0900576], P1),
                            P2 is 1-P1
                        )
                    ;   % n = 0, too few groundings for a model of its own: the parent's model, logistic
                        logistic([Distance], [-36.505, 0.0900576], P1),
                        P2 is 1-P1
                    )
                ;   kind(Occluder):t+1 ~= box
                ->  (   lost_anywhere(Occluded):t
                    ->  (   seen(Occluder):t
                        ->  % n = 188 (weight 692), log-likelihood -0.997837, finite
                            P1 = 0.00144092,
                            P2 = 0.99855908
                        ;   % n = 13 (weight 25), log-likelihood -4.54755, logistic
                            logistic([Distance], [-14.7079, 0.727959], P1),
                            P2 is 1-P1
                        )
                    ;   % n = 4800 (weight 12980), log-likelihood -1748.57, logistic
                        logistic([Distance], [-23.6996, 1.42683], P1),
                        P2 is 1-P1
                    )
                ;   kind(Occluder):t+1 ~= can
                ->  % n = 1193 (weight 4933), log-likelihood -0.999696, finite
                    P1 = 0.000202634,
                    P2 = 0.999797366
                ;   kind(Occluder):t+1 ~= cup
                ->  (   seen(Occluded):t
                    ->  % n = 98, log-likelihood -7.94443, logistic
                        logistic([Distance], [-34.7722, 2.01006], P1),
                        P2 is 1-P1
                    ;   % n = 4889 (weight 11841), log-likelihood -3815.49, logistic
                        logistic([Distance], [-12.7232, 0.905301], P1),
                        P2 is 1-P1
                    )
                ;   kind(Occluder):t+1 ~= mug
                ->  (   lost_anywhere(Occluded):t
                    ->  (   seen(Occluder):t
                        ->  % n = 184 (weight 652), log-likelihood -0.997705, finite
                            P1 = 0.00152905,
                            P2 = 0.99847095
                        ;   % n = 14 (weight 22), log-likelihood -5.42227, logistic
                            logistic([Distance], [-18.255, 3.22144], P1),
                            P2 is 1-P1
                        )
                    ;   % n = 4789 (weight 10833), log-likelihood -2973.13, logistic
                        logistic([Distance], [-18.4185, 1.64392], P1),
                        P2 is 1-P1
                    )
                ;   kind(Occluder):t+1 ~= skin
                ->  % n = 1065 (weight 1385), log-likelihood -315.554, logistic
                    logistic([Distance], [-11.0194, -0.334481], P1),
                    P2 is 1-P1
                ;   \+ kind(Occluder):t+1 ~= _
                ->  % n = 0, too few groundings for a model of its own: the parent's model, logistic
                    logistic([Distance], [-17.5105, 1.0551], P1),
                    P2 is 1-P1
                )
            ;   kind(Occluded):t+1 ~= box
            ->  % n = 1038 (weight 2646), log-likelihood -29.8094, logistic
                logistic([Distance], [-34.808, -1.54843], P1),
                P2 is 1-P1
            ;   kind(Occluded):t+1 ~= can
            ->  % n = 1465 (weight 3781), log-likelihood -64.3195, logistic
                logistic([Distance], [-86.5233, 5.47533], P1),
                P2 is 1-P1
            ;   kind(Occluded):t+1 ~= cup
            ->  % n = 867 (weight 1863), log-likelihood -61.7069, logistic
                logistic([Distance], [-18.5503, -2.30772], P1),
                P2 is 1-P1
            ;   kind(Occluded):t+1 ~= mug
            ->  (   kind(Occluder):t+1 ~= ball
                ->  % n = 224 (weight 712), log-likelihood -0.997898, finite
                    P1 = 0.00140056,
                    P2 = 0.99859944
                ;   kind(Occluder):t+1 ~= box
                ->  % n = 771 (weight 1583), log-likelihood -15.0573, logistic
                    logistic([Distance], [-117.34, 4.8919], P1),
                    P2 is 1-P1
                ;   kind(Occluder):t+1 ~= can
                ->  % n = 53 (weight 129), log-likelihood -0.988511, finite
                    P1 = 0.00763359,
                    P2 = 0.99236641
                ;   kind(Occluder):t+1 ~= cup
                ->  % n = 244 (weight 692), log-likelihood -51.9469, logistic
                    logistic([Distance], [-27.9901, 0.94222], P1),
                    P2 is 1-P1
                ;   kind(Occluder):t+1 ~= mug
                ->  % n = 386 (weight 1018), log-likelihood -7.86785, logistic
                    logistic([Distance], [-62.3765, 3.56427], P1),
                    P2 is 1-P1
                ;   kind(Occluder):t+1 ~= skin
                ->  % n = 206 (weight 246), log-likelihood -60.5457, logistic
                    logistic([Distance], [-15.7469, 1.11947], P1),
                    P2 is 1-P1
                ;   \+ kind(Occluder):t+1 ~= _
                ->  % n = 0, too few groundings for a model of its own: the parent's model, logistic
                    logistic([Distance], [-52.605, 3.03894], P1),
                    P2 is 1-P1
                )
            ;   kind(Occluded):t+1 ~= skin
            ->  % n = 312 (weight 1192), log-likelihood -0.998743, finite
                P1 = 0.000837521,
                P2 = 0.999162479
            ;   \+ kind(Occluded):t+1 ~= _
            ->  % n = 0, too few groundings for a model of its own: the parent's model, logistic
                logistic([Distance], [-19.0095, 1.00986], P1),
                P2 is 1-P1
            )
        )
    ;   % n = 0, too few groundings for a model of its own: the parent's model, finite
        P1 = 0.210879,
        P2 = 0.789121
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

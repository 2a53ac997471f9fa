/*  too_learned_hindsight.pl -- the theory of occlusion with rules learned from experience.

    Written by `anchoring learn-theory`: a tree learned (ddc learn) from
    data_hindsight.pl: 26752 groundings of occluder(A, O):t+1,
    42 clauses, training log-likelihood -9484.71;
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
hides(ball, 0.001147).  % 3,485
hides(box, 0.1849).  % 12,568
hides(can, 0.0002619).  % 3,816
hides(cup, 0.2192).  % 10,252
hides(mug, 0.2534).  % 10,401
hides(skin, 0.4047).  % 1,604
hidden_share(ball, 0.2312).  % 30,337
hidden_share(box, 0.002674).  % 2,616
hidden_share(can, 0.181).  % 2,816
hidden_share(cup, 0.00813).  % 1,843
hidden_share(mug, 0.09537).  % 3,322
hidden_share(skin, 0.0008375).  % 1,192
carries(box, 0.9744).  % 37
carries(skin, 0.9969).  % 316
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

% occluder(Occluded, Occluder):t+1: 42 clauses, 26752 groundings, training log-likelihood -9484.71 (mean -0.136212 per grounding), 62 parameters.
occluder(Occluded, Occluder):t+1 ~ finite([P1:true, P2:false]) :=
    pair(Occluded, Occluder):t+1,
    (   distance(Occluded, Occluder):t+1 ~= Distance
    ->  (   occluded_by(Occluded, Occluder):t
        ->  % n = 2471 (weight 7759), log-likelihood -0.999807, finite
            P1 = 0.999871151,
            P2 = 0.000128849
        ;   (   kind(Occluder):t+1 ~= ball
            ->  (   rise(Occluded, Occluder):t+1 ~= Rise
                ->  (   Rise < 0.0
                    ->  % n = 1117 (weight 3297), log-likelihood -0.999545, finite
                        P1 = 0.000303122,
                        P2 = 0.999696878
                    ;   Rise < 0.1
                    ->  % n = 594 (weight 2102), log-likelihood -3.5711, logistic
                        logistic([Distance], [-51.5064, 2.61982], P1),
                        P2 is 1-P1
                    ;   % n = 0, too few groundings for a model of its own: the parent's model, logistic
                        logistic([Distance], [-37.1808, -0.579868], P1),
                        P2 is 1-P1
                    )
                ;   % n = 0, too few groundings for a model of its own: the parent's model, logistic
                    logistic([Distance], [-37.1808, -0.579868], P1),
                    P2 is 1-P1
                )
            ;   kind(Occluder):t+1 ~= box
            ->  (   kind(Occluded):t+1 ~= ball
                ->  (   lost_anywhere(Occluded):t
                    ->  (   seen(Occluder):t
                        ->  % n = 190 (weight 702), log-likelihood -0.997868, finite
                            P1 = 0.00142045,
                            P2 = 0.99857955
                        ;   % n = 13 (weight 25), log-likelihood -4.54755, logistic
                            logistic([Distance], [-14.7079, 0.727959], P1),
                            P2 is 1-P1
                        )
                    ;   % n = 4892 (weight 13328), log-likelihood -1764.61, logistic
                        logistic([Distance], [-23.9705, 1.41833], P1),
                        P2 is 1-P1
                    )
                ;   kind(Occluded):t+1 ~= box
                ->  % n = 242 (weight 650), log-likelihood -28.0454, logistic
                    logistic([Distance], [-36.2609, -1.26867], P1),
                    P2 is 1-P1
                ;   kind(Occluded):t+1 ~= can
                ->  % n = 651 (weight 1227), log-likelihood -53.5439, logistic
                    logistic([Distance], [-72.7401, 4.76722], P1),
                    P2 is 1-P1
                ;   kind(Occluded):t+1 ~= cup
                ->  % n = 276 (weight 676), log-likelihood -7.82009, finite
                    P1 = 0.00294985,
                    P2 = 0.99705015
                ;   kind(Occluded):t+1 ~= mug
                ->  % n = 769 (weight 1585), log-likelihood -15.0628, logistic
                    logistic([Distance], [-117.219, 4.89118], P1),
                    P2 is 1-P1
                ;   kind(Occluded):t+1 ~= skin
                ->  % n = 49 (weight 141), log-likelihood -0.989478, finite
                    P1 = 0.00699301,
                    P2 = 0.99300699
                ;   \+ kind(Occluded):t+1 ~= _
                ->  % n = 0, too few groundings for a model of its own: the parent's model, logistic
                    logistic([Distance], [-24.1648, 0.942878], P1),
                    P2 is 1-P1
                )
            ;   kind(Occluder):t+1 ~= can
            ->  % n = 1523 (weight 6035), log-likelihood -0.999752, finite
                P1 = 0.000165645,
                P2 = 0.999834355
            ;   kind(Occluder):t+1 ~= cup
            ->  (   kind(Occluded):t+1 ~= ball
                ->  (   seen(Occluded):t
                    ->  % n = 98, log-likelihood -7.94443, logistic
                        logistic([Distance], [-34.7722, 2.01006], P1),
                        P2 is 1-P1
                    ;   % n = 4973 (weight 12125), log-likelihood -3801.23, logistic
                        logistic([Distance], [-12.8758, 0.936728], P1),
                        P2 is 1-P1
                    )
                ;   kind(Occluded):t+1 ~= box
                ->  % n = 222 (weight 690), log-likelihood -0.997831, finite
                    P1 = 0.00144509,
                    P2 = 0.99855491
                ;   kind(Occluded):t+1 ~= can
                ->  % n = 221 (weight 845), log-likelihood -5.74148, logistic
                    logistic([Distance], [-60.5621, 2.94554], P1),
                    P2 is 1-P1
                ;   kind(Occluded):t+1 ~= cup
                ->  % n = 66 (weight 126), log-likelihood -0.98824, finite
                    P1 = 0.0078125,
                    P2 = 0.9921875
                ;   kind(Occluded):t+1 ~= mug
                ->  % n = 234 (weight 642), log-likelihood -52.3119, logistic
                    logistic([Distance], [-26.288, 0.741892], P1),
                    P2 is 1-P1
                ;   kind(Occluded):t+1 ~= skin
                ->  % n = 151 (weight 607), log-likelihood -0.997535, finite
                    P1 = 0.00164204,
                    P2 = 0.99835796
                ;   \+ kind(Occluded):t+1 ~= _
                ->  % n = 0, too few groundings for a model of its own: the parent's model, logistic
                    logistic([Distance], [-13.6795, 0.825467], P1),
                    P2 is 1-P1
                )
            ;   kind(Occluder):t+1 ~= mug
            ->  (   kind(Occluded):t+1 ~= ball
                ->  (   lost_anywhere(Occluded):t
                    ->  (   seen(Occluder):t
                        ->  % n = 183 (weight 647), log-likelihood -0.997687, finite
                            P1 = 0.00154083,
                            P2 = 0.99845917
                        ;   % n = 14 (weight 22), log-likelihood -5.42227, logistic
                            logistic([Distance], [-18.255, 3.22144], P1),
                            P2 is 1-P1
                        )
                    ;   % n = 4865 (weight 11037), log-likelihood -2949.75, logistic
                        logistic([Distance], [-18.5574, 1.67578], P1),
                        P2 is 1-P1
                    )
                ;   kind(Occluded):t+1 ~= box
                ->  % n = 270 (weight 634), log-likelihood -0.99764, finite
                    P1 = 0.00157233,
                    P2 = 0.99842767
                ;   kind(Occluded):t+1 ~= can
                ->  % n = 396 (weight 1172), log-likelihood -5.7227, logistic
                    logistic([Distance], [-81.4757, 6.49308], P1),
                    P2 is 1-P1
                ;   kind(Occluded):t+1 ~= cup
                ->  % n = 206 (weight 490), log-likelihood -5.00591, logistic
                    logistic([Distance], [-50.4883, 3.64425], P1),
                    P2 is 1-P1
                ;   kind(Occluded):t+1 ~= mug
                ->  % n = 381 (weight 993), log-likelihood -7.77371, logistic
                    logistic([Distance], [-62.4628, 3.58639], P1),
                    P2 is 1-P1
                ;   kind(Occluded):t+1 ~= skin
                ->  % n = 15 (weight 59), log-likelihood -0.975229, finite
                    P1 = 0.0163934,
                    P2 = 0.9836066
                ;   \+ kind(Occluded):t+1 ~= _
                ->  % n = 0, too few groundings for a model of its own: the parent's model, logistic
                    logistic([Distance], [-20.7937, 1.64285], P1),
                    P2 is 1-P1
                )
            ;   kind(Occluder):t+1 ~= skin
            ->  (   kind(Occluded):t+1 ~= ball
                ->  (   lost_anywhere(Occluded):t
                    ->  % n = 101 (weight 113), log-likelihood -0.986906, finite
                        P1 = 0.00869565,
                        P2 = 0.99130435
                    ;   % n = 1142 (weight 1298), log-likelihood -739.938, logistic
                        logistic([Distance], [-7.24139, 1.30175], P1),
                        P2 is 1-P1
                    )
                ;   kind(Occluded):t+1 ~= box
                ->  % n = 58, log-likelihood -0.974813, finite
                    P1 = 0.0166667,
                    P2 = 0.9833333
                ;   kind(Occluded):t+1 ~= can
                ->  % n = 42 (weight 50), log-likelihood -0.970904, finite
                    P1 = 0.0192308,
                    P2 = 0.9807692
                ;   kind(Occluded):t+1 ~= cup
                ->  % n = 120 (weight 152), log-likelihood -0.990232, finite
                    P1 = 0.00649351,
                    P2 = 0.99350649
                ;   kind(Occluded):t+1 ~= mug
                ->  % n = 207 (weight 247), log-likelihood -11.8074, finite
                    P1 = 0.0120482,
                    P2 = 0.9879518
                ;   kind(Occluded):t+1 ~= skin
                ->  % n = 0, too few groundings for a model of its own: the parent's model, logistic
                    logistic([Distance], [-6.96518, 0.584911], P1),
                    P2 is 1-P1
                ;   \+ kind(Occluded):t+1 ~= _
                ->  % n = 0, too few groundings for a model of its own: the parent's model, logistic
                    logistic([Distance], [-6.96518, 0.584911], P1),
                    P2 is 1-P1
                )
            ;   \+ kind(Occluder):t+1 ~= _
            ->  % n = 0, too few groundings for a model of its own: the parent's model, logistic
                logistic([Distance], [-17.8635, 0.970169], P1),
                P2 is 1-P1
            )
        )
    ;   % n = 0, too few groundings for a model of its own: the parent's model, finite
        P1 = 0.219893,
        P2 = 0.780107
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

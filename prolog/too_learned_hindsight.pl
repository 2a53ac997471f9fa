/*  too_learned_hindsight.pl -- the theory of occlusion with rules learned from experience.

    Written by `anchoring learn-theory`: a tree learned (ddc learn) from
    data_hindsight.pl: 23602 groundings of occluder(A, O):t+1,
    60 clauses, training log-likelihood -3100.08;
    and one for released(A):t+1 from 803 frames a hand held an object
    (3 clauses, training log-likelihood -27.7059);
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
obs_var(2.749e-06).  % the measurement noise of a perceived position (m², per axis); 68,866 samples
motion_var(3.22e-05).  % how far a perceived object moves in a frame (m², per axis); 95,200 samples
reappear_var(0.001674).  % where a hidden object is seen again, around its belief (m²); 464 samples
lost_var(0.0662).  % the same for an object lost while the camera saw nothing (m²); 6,422 samples
follow_keep(0.5763).  % the fraction of its offset from its occluder a hidden object keeps; 52 samples
follow_var(1e-08).  % the jitter of that offset per frame (m²); 52 samples
coast_keep(0.8936).  % the fraction of its velocity a hidden object under nothing keeps; 269 samples
wander_var(0.0001389).  % how far such an object may move besides (m²); 269 samples
grip_reach(0.03524).  % how far (table plane) a hand's grip may be from what it takes (m); 18 samples
grip_height(0.126).  % how far above it (m); 18 samples
occluder_rise(0).  % how far below its centre (m); 18 samples
grip_drop(0.02279).  % how far what a hand holds is below its grip (m); 18 samples
grip_rise(0.001665).  % how far a hand's grip rises in a frame when it lifts (m); 216 samples

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
hides(ball, 0.0007968).  % 5,018
hides(box, 0.2662).  % 10,667
hides(can, 0.002185).  % 3,202
hides(cup, 0.1858).  % 6,792
hides(mug, 0.1238).  % 8,583
hides(skin, 0.4561).  % 1,855
hidden_share(ball, 0.2002).  % 16,563
hidden_share(box, 0.03905).  % 3,020
hidden_share(can, 0.1297).  % 4,409
hidden_share(cup, 0.1791).  % 4,783
hidden_share(mug, 0.1878).  % 6,171
hidden_share(skin, 0.0008525).  % 1,171
carries(box, 0.9773).  % 42
carries(skin, 0.9974).  % 386
carrier(skin).
can_occlude(O) := category(O, C), hides(C, P), P >= 0.01, \+ is_carrier(O).
is_carrier(O) := category(O, C), carrier(C).
hand_known := object(O), is_carrier(O).
can_be_occluded(A) := category(A, C), hidden_share(C, P), P >= 0.01.

:- include('too/too_learned_glue.pl').
% The onset reach (m): 90% of the 81 onsets in the data were within 0.0675 m; times 2.0.
onset_reach(0.135).

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

% occluder(Occluded, Occluder):t+1: 60 clauses, 23602 groundings, training log-likelihood -3100.08 (mean -0.053031 per grounding), 88 parameters.
occluder(Occluded, Occluder):t+1 ~ finite([P1:true, P2:false]) :=
    pair(Occluded, Occluder):t+1,
    (   distance(Occluded, Occluder):t+1 ~= Distance
    ->  (   kind(Occluder):t+1 ~= ball
        ->  (   rise(Occluded, Occluder):t+1 ~= Rise
            ->  (   Rise < 0.0
                ->  % n = 1441 (weight 4245), log-likelihood -0.999647, finite
                    P1 = 0.00023546,
                    P2 = 0.99976454
                ;   Rise < 0.1
                ->  % n = 970 (weight 3618), log-likelihood -4.53959, logistic
                    logistic([Distance], [-54.8071, 2.53469], P1),
                    P2 is 1-P1
                ;   % n = 0, too few groundings for a model of its own: the parent's model, logistic
                    logistic([Distance], [-47.1362, 0.522735], P1),
                    P2 is 1-P1
                )
            ;   % n = 0, too few groundings for a model of its own: the parent's model, logistic
                logistic([Distance], [-47.1362, 0.522735], P1),
                P2 is 1-P1
            )
        ;   kind(Occluder):t+1 ~= box
        ->  (   lost_anywhere(Occluded):t
            ->  (   seen(Occluder):t
                ->  % n = 335 (weight 1059), log-likelihood -0.998586, finite
                    P1 = 0.000942507,
                    P2 = 0.999057493
                ;   % n = 28 (weight 32), log-likelihood -19.025, finite
                    P1 = 0.294118,
                    P2 = 0.705882
                )
            ;   (   rise(Occluded, Occluder):t+1 ~= Rise4
                ->  (   Rise4 < 0.0
                    ->  (   kind(Occluded):t+1 ~= ball
                        ->  % n = 0, too few groundings for a model of its own: the parent's model, logistic
                            logistic([Distance], [-162.733, -0.198693], P1),
                            P2 is 1-P1
                        ;   kind(Occluded):t+1 ~= box
                        ->  % n = 40 (weight 128), log-likelihood -0.988422, finite
                            P1 = 0.00769231,
                            P2 = 0.99230769
                        ;   kind(Occluded):t+1 ~= can
                        ->  % n = 162 (weight 646), log-likelihood -0.997684, finite
                            P1 = 0.00154321,
                            P2 = 0.99845679
                        ;   kind(Occluded):t+1 ~= cup
                        ->  % n = 68 (weight 116), log-likelihood -0.749321, logistic
                            logistic([Distance], [-63.0829, 6.57966], P1),
                            P2 is 1-P1
                        ;   kind(Occluded):t+1 ~= mug
                        ->  % n = 11, log-likelihood -1.28628, logistic
                            logistic([Distance], [-23.6193, 4.1783], P1),
                            P2 is 1-P1
                        ;   kind(Occluded):t+1 ~= skin
                        ->  % n = 64 (weight 220), log-likelihood -0.99323, finite
                            P1 = 0.0045045,
                            P2 = 0.9954955
                        ;   \+ kind(Occluded):t+1 ~= _
                        ->  % n = 0, too few groundings for a model of its own: the parent's model, logistic
                            logistic([Distance], [-162.733, -0.198693], P1),
                            P2 is 1-P1
                        )
                    ;   Rise4 < 0.1
                    ->  (   kind(Occluded):t+1 ~= ball
                        ->  (   occluded_by(Occluded, Occluder):t
                            ->  % n = 96 (weight 296), log-likelihood -0.994959, finite
                                P1 = 0.9966443,
                                P2 = 0.0033557
                            ;   % n = 1849 (weight 5693), log-likelihood -262.443, logistic
                                logistic([Distance], [-51.7391, 2.64592], P1),
                                P2 is 1-P1
                            )
                        ;   kind(Occluded):t+1 ~= box
                        ->  % n = 49 (weight 141), log-likelihood -10.6756, finite
                            P1 = 0.020979,
                            P2 = 0.979021
                        ;   kind(Occluded):t+1 ~= can
                        ->  % n = 1089 (weight 2361), log-likelihood -100.275, logistic
                            logistic([Distance], [-97.7039, 5.03775], P1),
                            P2 is 1-P1
                        ;   kind(Occluded):t+1 ~= cup
                        ->  % n = 1116 (weight 1984), log-likelihood -32.2837, logistic
                            logistic([Distance], [-96.9349, 9.33687], P1),
                            P2 is 1-P1
                        ;   kind(Occluded):t+1 ~= mug
                        ->  % n = 1920 (weight 3648), log-likelihood -10.7575, logistic
                            logistic([Distance], [-157.23, 9.70455], P1),
                            P2 is 1-P1
                        ;   kind(Occluded):t+1 ~= skin
                        ->  % n = 8, too few groundings for a model of its own: the parent's model, log-likelihood -3.62037e-05, logistic
                            logistic([Distance], [-78.0826, 5.15409], P1),
                            P2 is 1-P1
                        ;   \+ kind(Occluded):t+1 ~= _
                        ->  % n = 0, too few groundings for a model of its own: the parent's model, logistic
                            logistic([Distance], [-78.0826, 5.15409], P1),
                            P2 is 1-P1
                        )
                    ;   % n = 823 (weight 1015), log-likelihood -98.9096, logistic
                        logistic([Distance], [-48.8733, 2.91817], P1),
                        P2 is 1-P1
                    )
                ;   % n = 0, too few groundings for a model of its own: the parent's model, logistic
                    logistic([Distance], [-54.6257, 3.14637], P1),
                    P2 is 1-P1
                )
            )
        ;   kind(Occluder):t+1 ~= can
        ->  % n = 1412 (weight 5040), log-likelihood -8.63626, logistic
            logistic([Distance], [-70.6103, 4.51081], P1),
            P2 is 1-P1
        ;   kind(Occluder):t+1 ~= cup
        ->  (   kind(Occluded):t+1 ~= ball
            ->  (   occluded_by(Occluded, Occluder):t
                ->  % n = 380 (weight 1104), log-likelihood -0.998643, finite
                    P1 = 0.999095841,
                    P2 = 0.000904159
                ;   % n = 2531 (weight 6003), log-likelihood -912.294, logistic
                    logistic([Distance], [-28.2779, 2.99532], P1),
                    P2 is 1-P1
                )
            ;   kind(Occluded):t+1 ~= box
            ->  (   rise(Occluded, Occluder):t+1 ~= Rise8
                ->  (   Rise8 < 0.0
                    ->  % n = 220 (weight 720), log-likelihood -5.62394, logistic
                        logistic([Distance], [-61.1974, 0.786234], P1),
                        P2 is 1-P1
                    ;   Rise8 < 0.1
                    ->  (   lift(Occluder):t+1 ~= Lift
                        ->  % n = 194 (weight 346), log-likelihood -36.4644, logistic
                            logistic([Distance, Lift], [-153.047, -516.105, 14.1114], P1),
                            P2 is 1-P1
                        ;   % n = 0, too few groundings for a model of its own: the parent's model, logistic
                            logistic([Distance], [-128.92, 10.8539], P1),
                            P2 is 1-P1
                        )
                    ;   % n = 8, too few groundings for a model of its own: the parent's model, log-likelihood -0.000923912, logistic
                        logistic([Distance], [-91.4364, 6.4241], P1),
                        P2 is 1-P1
                    )
                ;   % n = 0, too few groundings for a model of its own: the parent's model, logistic
                    logistic([Distance], [-91.4364, 6.4241], P1),
                    P2 is 1-P1
                )
            ;   kind(Occluded):t+1 ~= can
            ->  % n = 91 (weight 243), log-likelihood -0.993866, finite
                P1 = 0.00408163,
                P2 = 0.99591837
            ;   kind(Occluded):t+1 ~= cup
            ->  % n = 256 (weight 728), log-likelihood -0.997944, finite
                P1 = 0.00136986,
                P2 = 0.99863014
            ;   kind(Occluded):t+1 ~= mug
            ->  (   seen(Occluded):t
                ->  % n = 83, log-likelihood -0.98226, finite
                    P1 = 0.0117647,
                    P2 = 0.9882353
                ;   % n = 331 (weight 1303), log-likelihood -9.36032, logistic
                    logistic([Distance], [-123.97, 15.9929], P1),
                    P2 is 1-P1
                )
            ;   kind(Occluded):t+1 ~= skin
            ->  % n = 92 (weight 412), log-likelihood -0.996373, finite
                P1 = 0.00241546,
                P2 = 0.99758454
            ;   \+ kind(Occluded):t+1 ~= _
            ->  % n = 0, too few groundings for a model of its own: the parent's model, logistic
                logistic([Distance], [-34.6637, 3.02912], P1),
                P2 is 1-P1
            )
        ;   kind(Occluder):t+1 ~= mug
        ->  (   occluded_by(Occluded, Occluder):t
            ->  % n = 335 (weight 1027), log-likelihood -0.998542, finite
                P1 = 0.999028183,
                P2 = 0.000971817
            ;   (   kind(Occluded):t+1 ~= ball
                ->  % n = 2802 (weight 6466), log-likelihood -835.74, logistic
                    logistic([Distance], [-32.2241, 2.40755], P1),
                    P2 is 1-P1
                ;   kind(Occluded):t+1 ~= box
                ->  % n = 430 (weight 1394), log-likelihood -0.998925, finite
                    P1 = 0.000716332,
                    P2 = 0.999283668
                ;   kind(Occluded):t+1 ~= can
                ->  % n = 626 (weight 1854), log-likelihood -41.8249, logistic
                    logistic([Distance], [-30.6378, -0.291126], P1),
                    P2 is 1-P1
                ;   kind(Occluded):t+1 ~= cup
                ->  (   rise(Occluded, Occluder):t+1 ~= Rise12
                    ->  (   Rise12 < 0.0
                        ->  % n = 76 (weight 180), log-likelihood -32.7344, logistic
                            logistic([Distance], [-24.0567, 2.5437], P1),
                            P2 is 1-P1
                        ;   Rise12 < 0.1
                        ->  % n = 483 (weight 1499), log-likelihood -49.5081, logistic
                            logistic([Distance], [-21.4682, -1.07436], P1),
                            P2 is 1-P1
                        ;   % n = 26, log-likelihood -0.945559, finite
                            P1 = 0.0357143,
                            P2 = 0.9642857
                        )
                    ;   % n = 0, too few groundings for a model of its own: the parent's model, logistic
                        logistic([Distance], [-20.424, -0.370749], P1),
                        P2 is 1-P1
                    )
                ;   kind(Occluded):t+1 ~= mug
                ->  % n = 462 (weight 1562), log-likelihood -23.2335, logistic
                    logistic([Distance], [-28.5997, -1.11986], P1),
                    P2 is 1-P1
                ;   kind(Occluded):t+1 ~= skin
                ->  % n = 22 (weight 86), log-likelihood -0.982868, finite
                    P1 = 0.0113636,
                    P2 = 0.9886364
                ;   \+ kind(Occluded):t+1 ~= _
                ->  % n = 0, too few groundings for a model of its own: the parent's model, logistic
                    logistic([Distance], [-37.3772, 2.17644], P1),
                    P2 is 1-P1
                )
            )
        ;   kind(Occluder):t+1 ~= skin
        ->  (   kind(Occluded):t+1 ~= ball
            ->  (   occluded_by(Occluded, Occluder):t
                ->  % n = 616 (weight 824), log-likelihood -0.998183, finite
                    P1 = 0.99878935,
                    P2 = 0.00121065
                ;   (   lost_anywhere(Occluded):t
                    ->  % n = 54 (weight 62), log-likelihood -0.976398, finite
                        P1 = 0.015625,
                        P2 = 0.984375
                    ;   (   seen(Occluded):t
                        ->  % n = 32, log-likelihood -3.09204, logistic
                            logistic([Distance], [-51.3374, 3.57285], P1),
                            P2 is 1-P1
                        ;   % n = 1127 (weight 1175), log-likelihood -557.084, logistic
                            logistic([Distance], [-6.9719, 2.29969], P1),
                            P2 is 1-P1
                        )
                    )
                )
            ;   kind(Occluded):t+1 ~= box
            ->  % n = 25 (weight 33), log-likelihood -4.7451, finite
                P1 = 0.0571429,
                P2 = 0.9428571
            ;   kind(Occluded):t+1 ~= can
            ->  % n = 62 (weight 74), log-likelihood -0.980147, finite
                P1 = 0.0131579,
                P2 = 0.9868421
            ;   kind(Occluded):t+1 ~= cup
            ->  % n = 240 (weight 308), log-likelihood -0.995154, finite
                P1 = 0.00322581,
                P2 = 0.99677419
            ;   kind(Occluded):t+1 ~= mug
            ->  % n = 478 (weight 598), log-likelihood -19.0119, finite
                P1 = 0.00666667,
                P2 = 0.99333333
            ;   kind(Occluded):t+1 ~= skin
            ->  % n = 39 (weight 47), log-likelihood -0.969106, finite
                P1 = 0.0204082,
                P2 = 0.9795918
            ;   \+ kind(Occluded):t+1 ~= _
            ->  % n = 0, too few groundings for a model of its own: the parent's model, logistic
                logistic([Distance], [-12.9105, 2.31297], P1),
                P2 is 1-P1
            )
        ;   \+ kind(Occluder):t+1 ~= _
        ->  % n = 0, too few groundings for a model of its own: the parent's model, logistic
            logistic([Distance], [-31.0491, 2.26825], P1),
            P2 is 1-P1
        )
    ;   % n = 0, too few groundings for a model of its own: the parent's model, finite
        P1 = 0.214967,
        P2 = 0.785033
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

% released(Held):t+1: 3 clauses, 803 groundings, training log-likelihood -27.7059 (mean -0.034503 per grounding), 6 parameters.
released(Held):t+1 ~ finite([P1:true, P2:false]) :=
    carried(Held):t+1,
    (   height(Held):t+1 ~= Height
    ->  (   highest(Held):t+1 ~= Highest
        ->  % n = 803, log-likelihood -27.7059, logistic
            logistic([Height, Highest], [-72.0515, 34.1173, -6.11895], P1),
            P2 is 1-P1
        ;   % n = 0, too few groundings for a model of its own: the parent's model, logistic
            logistic([Height], [-45.272, -2.02445], P1),
            P2 is 1-P1
        )
    ;   % n = 0, too few groundings for a model of its own: the parent's model, finite
        P1 = 0.0236025,
        P2 = 0.9763975
    ).

:- include('too/too_motion.pl').

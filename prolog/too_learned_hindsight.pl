/*  too_learned_hindsight.pl -- the theory of occlusion with rules learned from experience.

    Written by `anchoring learn-theory`: a tree learned (ddc learn) from
    data_hindsight.pl: 26103 groundings of occluder(A, O):t+1,
    28 clauses, training log-likelihood -9359.52;
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
lift_margin(0.074).  % how high a carried object is lifted before it counts as picked up (m); 46 samples
release_margin(0.00952).  % how near where it stood it counts as put down (m); 46 samples
release_p(0.6866).  % the probability per frame that the hand lets go there; 65 samples
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
hides(ball, 0.001167).  % 3,425
hides(box, 0.1865).  % 13,333
hides(can, 0.0003084).  % 3,241
hides(cup, 0.2313).  % 10,137
hides(mug, 0.2615).  % 10,461
hides(skin, 0.1052).  % 1,509
hidden_share(ball, 0.2257).  % 30,281
hidden_share(box, 0.002671).  % 2,619
hidden_share(can, 0.1809).  % 2,829
hidden_share(cup, 0.01064).  % 1,877
hidden_share(mug, 0.1082).  % 3,308
hidden_share(skin, 0.0008375).  % 1,192
carries(box, 0.9677).  % 29
carries(skin, 0.9851).  % 65
carrier(skin).
can_occlude(O) := category(O, C), hides(C, P), P >= 0.01, \+ is_carrier(O).
is_carrier(O) := category(O, C), carrier(C).
hand_known := object(O), is_carrier(O).
can_be_occluded(A) := category(A, C), hidden_share(C, P), P >= 0.01.

:- include('too/too_learned_glue.pl').
% The onset reach (m): 90% of the 66 onsets in the data were within 0.09137 m; times 2.0.
onset_reach(0.1827).

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

% occluder(Occluded, Occluder):t+1: 28 clauses, 26103 groundings, training log-likelihood -9359.52 (mean -0.136853 per grounding), 45 parameters.
occluder(Occluded, Occluder):t+1 ~ finite([P1:true, P2:false]) :=
    pair(Occluded, Occluder):t+1,
    (   distance(Occluded, Occluder):t+1 ~= Distance
    ->  (   occluded_by(Occluded, Occluder):t
        ->  % n = 2246 (weight 7634), log-likelihood -0.999804, finite
            P1 = 0.999869041,
            P2 = 0.000130959
        ;   (   kind(Occluded):t+1 ~= ball
            ->  (   kind(Occluder):t+1 ~= ball
                ->  (   rise(Occluded, Occluder):t+1 ~= Rise
                    ->  (   Rise < 0.0
                        ->  % n = 539 (weight 1899), log-likelihood -0.999211, finite
                            P1 = 0.000526039,
                            P2 = 0.999473961
                        ;   Rise < 0.1
                        ->  % n = 427 (weight 1435), log-likelihood -3.78558, logistic
                            logistic([Distance], [-46.3561, 2.40104], P1),
                            P2 is 1-P1
                        ;   % n = 0, too few groundings for a model of its own: the parent's model, logistic
                            logistic([Distance], [-36.4706, 0.0885668], P1),
                            P2 is 1-P1
                        )
                    ;   % n = 0, too few groundings for a model of its own: the parent's model, logistic
                        logistic([Distance], [-36.4706, 0.0885668], P1),
                        P2 is 1-P1
                    )
                ;   kind(Occluder):t+1 ~= box
                ->  (   lost_anywhere(Occluded):t
                    ->  (   seen(Occluder):t
                        ->  % n = 243 (weight 967), log-likelihood -0.998451, finite
                            P1 = 0.00103199,
                            P2 = 0.99896801
                        ;   % n = 14 (weight 30), log-likelihood -4.5939, logistic
                            logistic([Distance], [-14.7634, 0.71021], P1),
                            P2 is 1-P1
                        )
                    ;   % n = 4844 (weight 13200), log-likelihood -1743.04, logistic
                        logistic([Distance], [-23.508, 1.43466], P1),
                        P2 is 1-P1
                    )
                ;   kind(Occluder):t+1 ~= can
                ->  % n = 1129 (weight 4613), log-likelihood -0.999675, finite
                    P1 = 0.000216685,
                    P2 = 0.999783315
                ;   kind(Occluder):t+1 ~= cup
                ->  % n = 5007 (weight 11755), log-likelihood -3987.04, logistic
                    logistic([Distance], [-12.2546, 0.918993], P1),
                    P2 is 1-P1
                ;   kind(Occluder):t+1 ~= mug
                ->  (   lost_anywhere(Occluded):t
                    ->  (   seen(Occluder):t
                        ->  % n = 191 (weight 687), log-likelihood -0.997822, finite
                            P1 = 0.00145138,
                            P2 = 0.99854862
                        ;   % n = 14 (weight 22), log-likelihood -6.71177, logistic
                            logistic([Distance], [-18.0297, 2.53124], P1),
                            P2 is 1-P1
                        )
                    ;   % n = 4815 (weight 10887), log-likelihood -2977.3, logistic
                        logistic([Distance], [-18.4878, 1.64759], P1),
                        P2 is 1-P1
                    )
                ;   kind(Occluder):t+1 ~= skin
                ->  % n = 1064 (weight 1380), log-likelihood -315.543, logistic
                    logistic([Distance], [-11.0131, -0.335431], P1),
                    P2 is 1-P1
                ;   \+ kind(Occluder):t+1 ~= _
                ->  % n = 0, too few groundings for a model of its own: the parent's model, logistic
                    logistic([Distance], [-17.1858, 1.0578], P1),
                    P2 is 1-P1
                )
            ;   kind(Occluded):t+1 ~= box
            ->  % n = 1035 (weight 2631), log-likelihood -30.014, logistic
                logistic([Distance], [-34.2758, -1.5906], P1),
                P2 is 1-P1
            ;   kind(Occluded):t+1 ~= can
            ->  % n = 1460 (weight 3756), log-likelihood -66.593, logistic
                logistic([Distance], [-83.8892, 5.43526], P1),
                P2 is 1-P1
            ;   kind(Occluded):t+1 ~= cup
            ->  % n = 877 (weight 1913), log-likelihood -64.7934, logistic
                logistic([Distance], [-19.1048, -2.17832], P1),
                P2 is 1-P1
            ;   kind(Occluded):t+1 ~= mug
            ->  (   kind(Occluder):t+1 ~= ball
                ->  % n = 226 (weight 722), log-likelihood -0.997927, finite
                    P1 = 0.00138122,
                    P2 = 0.99861878
                ;   kind(Occluder):t+1 ~= box
                ->  % n = 774 (weight 1598), log-likelihood -22.551, logistic
                    logistic([Distance], [-109.289, 4.74875], P1),
                    P2 is 1-P1
                ;   kind(Occluder):t+1 ~= can
                ->  % n = 51 (weight 119), log-likelihood -0.987558, finite
                    P1 = 0.00826446,
                    P2 = 0.99173554
                ;   kind(Occluder):t+1 ~= cup
                ->  % n = 245 (weight 697), log-likelihood -51.9538, logistic
                    logistic([Distance], [-27.8168, 0.923398], P1),
                    P2 is 1-P1
                ;   kind(Occluder):t+1 ~= mug
                ->  % n = 384 (weight 1008), log-likelihood -7.91792, logistic
                    logistic([Distance], [-61.8614, 3.53325], P1),
                    P2 is 1-P1
                ;   kind(Occluder):t+1 ~= skin
                ->  % n = 206 (weight 246), log-likelihood -69.7027, logistic
                    logistic([Distance], [-16.565, 1.69037], P1),
                    P2 is 1-P1
                ;   \+ kind(Occluder):t+1 ~= _
                ->  % n = 0, too few groundings for a model of its own: the parent's model, logistic
                    logistic([Distance], [-48.0383, 2.84919], P1),
                    P2 is 1-P1
                )
            ;   kind(Occluded):t+1 ~= skin
            ->  % n = 312 (weight 1192), log-likelihood -0.998743, finite
                P1 = 0.000837521,
                P2 = 0.999162479
            ;   \+ kind(Occluded):t+1 ~= _
            ->  % n = 0, too few groundings for a model of its own: the parent's model, logistic
                logistic([Distance], [-18.6373, 1.01157], P1),
                P2 is 1-P1
            )
        )
    ;   % n = 0, too few groundings for a model of its own: the parent's model, finite
        P1 = 0.217318,
        P2 = 0.782682
    ).

:- include('too/too_motion.pl').

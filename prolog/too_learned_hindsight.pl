/*  too_learned_hindsight.pl -- the theory of occlusion with rules learned from experience.

    Written by `anchoring learn-theory`: the hand-written occlusion rules of
    too.pl are replaced by a tree learned (ddc learn) from data_hindsight.pl:
    28680 groundings of occluder(A, O):t+1, 38 clauses,
    training log-likelihood -9712.18; search seed 0.
    Command: anchoring learn-theory out/learn/data_hindsight.pl --seed 0 --out prolog/too_learned_hindsight.pl --plots docs/images
    The hand-written parts are included from prolog/ (too_base.pl, too_knowledge.pl,
    too_motion.pl): regenerate this file rather than edit it; edit those for the rest.
*/

:- include('too_base.pl').
:- include('too_knowledge.pl').

% ------------------------------------------------------------------ learned occlusion rules
% How the learned occluder/2 (below) is used, as the paper's theory uses its occluder rule
% (section 2.3): the pairs it is about are a hidden A and a perceived O (the data's examples)
% that the affordances above allow (a ball hides nothing, a hand is never hidden: the paper's
% experiments keep that knowledge too; the tree gives a ball as occluder a probability of
% about 1e-4 per frame, and one particle of a hidden ball under the other, identical ball is
% enough for the matching, which takes the best particle, to swap them);
% O is a candidate occluder of the hidden A when the particle
% draws occluder(A, O):t+1 ~= true; the particle picks one candidate uniformly, or `behind`
% when A has just vanished (it stays where it was, hidden from view: as in too.pl); the
% occlusion goes on while O is perceived and the particle draws occluder(A, O):t+1 ~= true.
pair(A, O):t+1 :=
    hidden(A):t+1, observed(O), O \== A, can_be_occluded(A), can_occlude(O).
occluder_candidate(A, O):t+1 :=
    pair(A, O):t+1, \+ occluded_by(A, O):t, occluder(A, O):t+1 ~= true.
pick_occluder(A):t+1 ~ uniform(Os) :=
    hidden(A):t+1, seen(A):t, \+ occluded_by(A, _):t,
    findall_forward(O, occluder_candidate(A, O):t+1, Os0), sort(Os0, Os1), Os1 \== [],
    Os = [behind | Os1].
pick_occluder(A):t+1 ~ uniform(Os) :=
    hidden(A):t+1, \+ seen(A):t, \+ occluded_by(A, _):t,
    findall_forward(O, occluder_candidate(A, O):t+1, Os0), sort(Os0, Os), Os \== [].
occluded_by(A, O):t+1 := hidden(A):t+1, pick_occluder(A):t+1 ~= O, O \== behind.
occluded_by(A, O):t+1 :=
    occluded_by(A, O):t, pair(A, O):t+1, occluder(A, O):t+1 ~= true.

% The learned rules (ddc learn): a distributional logic tree for occluder/2 (each path from its
% root to a leaf is one clause of the tree), with the background knowledge it reads.
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

% occluder(Occluded, Occluder):t+1: 38 clauses, 28680 groundings, training log-likelihood -9712.18 (mean -0.128922 per grounding), 67 parameters.
occluder(Occluded, Occluder):t+1 ~ finite([P1:true, P2:false]) :=
    pair(Occluded, Occluder):t+1,
    (   distance(Occluded, Occluder):t+1 ~= Distance
    ->  (   occluded_by(Occluded, Occluder):t
        ->  % n = 2403 (weight 8081.35), log-likelihood -28.4281, logistic
            logistic([Distance], [-74.076, 7.93402], P1),
            P2 is 1-P1
        ;   (   kind(Occluded):t+1 ~= ball
            ->  (   kind(Occluder):t+1 ~= ball
                ->  (   rise(Occluded, Occluder):t+1 ~= Rise
                    ->  (   Rise < 0.0
                        ->  % n = 593 (weight 2117), log-likelihood -0.999292, finite
                            P1 = 0.000471921,
                            P2 = 0.999528079
                        ;   Rise < 0.1
                        ->  % n = 450 (weight 1478), log-likelihood -3.92495, logistic
                            logistic([Distance], [-46.2047, 2.3389], P1),
                            P2 is 1-P1
                        ;   % n = 0, too few groundings for a model of its own: the parent's model, logistic
                            logistic([Distance], [-36.1381, 0.00167557], P1),
                            P2 is 1-P1
                        )
                    ;   % n = 0, too few groundings for a model of its own: the parent's model, logistic
                        logistic([Distance], [-36.1381, 0.00167557], P1),
                        P2 is 1-P1
                    )
                ;   kind(Occluder):t+1 ~= box
                ->  (   lost_anywhere(Occluded):t
                    ->  (   seen(Occluder):t
                        ->  % n = 211 (weight 807), log-likelihood -0.998145, finite
                            P1 = 0.00123609,
                            P2 = 0.99876391
                        ;   % n = 15 (weight 31), log-likelihood -4.59763, logistic
                            logistic([Distance], [-15.1434, 0.709852], P1),
                            P2 is 1-P1
                        )
                    ;   % n = 4864 (weight 13240), log-likelihood -1744.81, logistic
                        logistic([Distance], [-23.6978, 1.44386], P1),
                        P2 is 1-P1
                    )
                ;   kind(Occluder):t+1 ~= can
                ->  % n = 1194 (weight 4878), log-likelihood -2.80907, logistic
                    logistic([Distance], [-58.3218, 2.23954], P1),
                    P2 is 1-P1
                ;   kind(Occluder):t+1 ~= cup
                ->  (   rise(Occluded, Occluder):t+1 ~= Rise4
                    ->  (   Rise4 < 0.0
                        ->  % n = 174 (weight 534), log-likelihood -29.3428, logistic
                            logistic([Distance], [-55.8819, -1.47057], P1),
                            P2 is 1-P1
                        ;   Rise4 < 0.1
                        ->  % n = 4662 (weight 10898), log-likelihood -3823.28, logistic
                            logistic([Distance], [-11.9924, 0.962263], P1),
                            P2 is 1-P1
                        ;   (   lift(Occluder):t+1 ~= Lift
                            ->  % n = 221 (weight 253), log-likelihood -36.9343, logistic
                                logistic([Distance, Lift], [-19.8593, 76.6907, 1.67714], P1),
                                P2 is 1-P1
                            ;   % n = 0, too few groundings for a model of its own: the parent's model, logistic
                                logistic([Distance], [-17.3878, 1.61301], P1),
                                P2 is 1-P1
                            )
                        )
                    ;   % n = 0, too few groundings for a model of its own: the parent's model, logistic
                        logistic([Distance], [-11.4484, 0.742624], P1),
                        P2 is 1-P1
                    )
                ;   kind(Occluder):t+1 ~= mug
                ->  (   lost_anywhere(Occluded):t
                    ->  (   seen(Occluder):t
                        ->  % n = 227 (weight 863), log-likelihood -0.998265, finite
                            P1 = 0.00115607,
                            P2 = 0.99884393
                        ;   % n = 15 (weight 23), log-likelihood -8.73935, logistic
                            logistic([Distance], [-13.9312, 1.58054], P1),
                            P2 is 1-P1
                        )
                    ;   (   rise(Occluded, Occluder):t+1 ~= Rise8
                        ->  (   Rise8 < 0.0
                            ->  % n = 45 (weight 105), log-likelihood -0.985923, finite
                                P1 = 0.00934579,
                                P2 = 0.99065421
                            ;   Rise8 < 0.1
                            ->  % n = 4631 (weight 10731), log-likelihood -2893.53, logistic
                                logistic([Distance], [-18.5087, 1.68891], P1),
                                P2 is 1-P1
                            ;   % n = 201 (weight 233), log-likelihood -55.7819, logistic
                                logistic([Distance], [-15.2393, 0.394428], P1),
                                P2 is 1-P1
                            )
                        ;   % n = 0, too few groundings for a model of its own: the parent's model, logistic
                            logistic([Distance], [-18.3173, 1.61318], P1),
                            P2 is 1-P1
                        )
                    )
                ;   kind(Occluder):t+1 ~= skin
                ->  % n = 1020 (weight 1392), log-likelihood -228.842, logistic
                    logistic([Distance], [-11.455, -0.81872], P1),
                    P2 is 1-P1
                ;   \+ kind(Occluder):t+1 ~= _
                ->  % n = 0, too few groundings for a model of its own: the parent's model, logistic
                    logistic([Distance], [-17.0031, 0.977971], P1),
                    P2 is 1-P1
                )
            ;   kind(Occluded):t+1 ~= box
            ->  (   seen(Occluded):t
                ->  % n = 301 (weight 300), log-likelihood -10.0772, logistic
                    logistic([Distance], [-39.5877, 2.64281], P1),
                    P2 is 1-P1
                ;   % n = 808 (weight 2491.4), log-likelihood -68.8348, logistic
                    logistic([Distance], [-35.3112, -0.681842], P1),
                    P2 is 1-P1
                )
            ;   kind(Occluded):t+1 ~= can
            ->  % n = 1538 (weight 3942), log-likelihood -66.789, logistic
                logistic([Distance], [-84.8809, 5.48788], P1),
                P2 is 1-P1
            ;   kind(Occluded):t+1 ~= cup
            ->  (   rise(Occluded, Occluder):t+1 ~= Rise12
                ->  (   Rise12 < 0.0
                    ->  % n = 291 (weight 567), log-likelihood -18.654, logistic
                        logistic([Distance], [-40.4883, 1.27194], P1),
                        P2 is 1-P1
                    ;   Rise12 < 0.1
                    ->  % n = 811 (weight 1874.26), log-likelihood -156.723, logistic
                        logistic([Distance], [-27.3944, -0.635822], P1),
                        P2 is 1-P1
                    ;   % n = 186 (weight 262), log-likelihood -10.2214, logistic
                        logistic([Distance], [-106.531, 5.89834], P1),
                        P2 is 1-P1
                    )
                ;   % n = 0, too few groundings for a model of its own: the parent's model, logistic
                    logistic([Distance], [-35.7469, 0.185191], P1),
                    P2 is 1-P1
                )
            ;   kind(Occluded):t+1 ~= mug
            ->  (   rise(Occluded, Occluder):t+1 ~= Rise16
                ->  (   Rise16 < 0.0
                    ->  (   lost_anywhere(Occluded):t
                        ->  % n = 187 (weight 715), log-likelihood -0.997907, finite
                            P1 = 0.0013947,
                            P2 = 0.9986053
                        ;   % n = 769 (weight 2122.63), log-likelihood -127.484, logistic
                            logistic([Distance], [-22.0013, -1.56282], P1),
                            P2 is 1-P1
                        )
                    ;   Rise16 < 0.1
                    ->  (   lost_anywhere(Occluded):t
                        ->  % n = 41 (weight 141), log-likelihood -0.989478, finite
                            P1 = 0.00699301,
                            P2 = 0.99300699
                        ;   % n = 1325 (weight 3169), log-likelihood -245.191, logistic
                            logistic([Distance], [-53.3228, 2.26704], P1),
                            P2 is 1-P1
                        )
                    ;   % n = 390 (weight 510.365), log-likelihood -103.27, logistic
                        logistic([Distance], [-14.8417, 0.149202], P1),
                        P2 is 1-P1
                    )
                ;   % n = 0, too few groundings for a model of its own: the parent's model, logistic
                    logistic([Distance], [-36.6755, 0.536202], P1),
                    P2 is 1-P1
                )
            ;   kind(Occluded):t+1 ~= skin
            ->  % n = 1135 (weight 3575), log-likelihood -37.9459, finite
                P1 = 0.00167738,
                P2 = 0.99832262
            ;   \+ kind(Occluded):t+1 ~= _
            ->  % n = 0, too few groundings for a model of its own: the parent's model, logistic
                logistic([Distance], [-18.2921, 0.763818], P1),
                P2 is 1-P1
            )
        )
    ;   % n = 0, too few groundings for a model of its own: the parent's model, finite
        P1 = 0.205644,
        P2 = 0.794356
    ).

:- include('too_motion.pl').

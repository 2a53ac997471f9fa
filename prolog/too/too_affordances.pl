/*  too_affordances.pl -- the hand-written affordances of the theory of occlusion.

    Included by too.pl: what can hide, be hidden or carry.  The theories `anchoring
    learn-theory` writes have affordances read from the data instead (with their
    probabilities), defining the same can_occlude/1, is_carrier/1, hand_known/0 and
    can_be_occluded/1.
*/

% ------------------------------------------------------------------ background knowledge
% Affordances, as the paper's experiments keep them beside learned rules (section 5.2).
% What cannot hide anything: a ball does not afford occluding, nor does a can or a bottle
% (closed, it stands upright and contains nothing that could be put under it).
cannot_occlude(ball) := true.
cannot_occlude(can) := true.
cannot_occlude(bottle) := true.
% What cannot be hidden by other objects: hands (skin) are not anchored inside anything.
cannot_be_occluded(skin) := true.
cannot_be_occluded(hand) := true.
% What carries what it hides through space (a hand lifts a grasped object); containers slide
% over the table and what they cover stays on the table.
carrier(skin) := true.
carrier(hand) := true.

% A carrier does not cover things as a container does: it closes over them and carries them
% (the carriers' rules, too_motion.pl).
can_occlude(O) := category(O, C), \+ cannot_occlude(C), \+ carrier(C).
is_carrier(O) := category(O, C), carrier(C).
hand_known := object(O), is_carrier(O).
can_be_occluded(A) := category(A, C), \+ cannot_be_occluded(C).

/*  too_knowledge.pl -- the hand-written parameters and affordances of the theory of occlusion.

    Included by too.pl (and, until they are learned, by the theories `anchoring learn-theory`
    writes): the motion and occlusion constants, what can hide, be hidden or carry, and what
    the camera seeing nothing means for an object lost then.
*/

% ------------------------------------------------------------------ parameters
% Variances are per axis, in square metres; one step is one camera frame.
motion_var(0.0004).         % how far a perceived object moves in one frame: (2 cm)^2
reappear_var(0.0025).       % where a hidden object shows up again, around its belief: (5 cm)^2
lost_var(0.09).             % where an object lost while the camera saw nothing shows up again:
                            % (30 cm)^2 around its belief (it may have been moved anywhere)
follow_var(0.000004).       % jitter of a hidden object that follows its occluder: (2 mm)^2
wander_var(0.0001).         % how far a hidden object under nothing may move in a frame: (1 cm)^2
coast_keep(0.9).            % fraction of its velocity a hidden object under nothing keeps per frame
follow_keep(0.95).          % fraction of its offset from the occluder's centre kept per frame
occluder_reach(0.15).       % an occluder is within 15 cm of the object in the table plane ...
occluder_rise(0.02).        % ... and its centre is no more than 2 cm lower than the object's
lowering_speed(0.003).      % an occluder coming down sinks by more than this per frame (m) ...
lowered_reach(0.05).        % ... onto an object within this distance in the table plane (m)
behind_when_covered(0.1).   % the probability that an object vanishing as an occluder comes down
                            % onto it is hidden by something else
cover_height(0.12).         % a container whose centre rises more than this above the object's
                            % centre no longer covers it (it was lifted)
grip_reach(0.06).           % a carrier (a hand) closes over an object within 6 cm of where it
grip_height(0.1).           % grips in the table plane, its grip at most 10 cm above the object
lift_margin(0.03).          % a carried object lifted 3 cm above where it stood was picked up ...
release_margin(0.02).       % ... and is put down when carried back within 2 cm of that height,
release_p(0.6).             % ... where the hand lets go of it with this probability per frame
grip_drop(0.02).            % what a hand holds is about 2 cm below its grip point
grip_rise(0.01).            % a hand rises when its grip goes up more than 1 cm in a frame

% ------------------------------------------------------------------ background knowledge
% Affordances (anchoring learn-theory keeps them beside the learned rules, as the paper's
% experiments keep them, section 5.2).
% What cannot hide anything: a ball does not afford occluding, nor does a can (closed, it
% stands upright and contains nothing that could be put under it).
cannot_occlude(ball) := true.
cannot_occlude(can) := true.
% What cannot be hidden by other objects: hands (skin) are not anchored inside anything.
cannot_be_occluded(skin) := true.
cannot_be_occluded(hand) := true.
% What carries what it hides through space (a hand lifts a grasped object); containers slide
% over the table and what they cover stays on the table.
carrier(skin) := true.
carrier(hand) := true.

% A carrier does not cover things as a container does: it closes over them and carries them
% (the carriers' rules below, kept beside learned occlusion rules as the affordances are).
can_occlude(O) := category(O, C), \+ cannot_occlude(C), \+ carrier(C).
is_carrier(O) := category(O, C), carrier(C).
hand_known := object(O), is_carrier(O).
can_be_occluded(A) := category(A, C), \+ cannot_be_occluded(C).

% An object hidden while blind stays "lost anywhere" until an occluder explains it.
lost_anywhere(A):t+1 := hidden(A):t+1, blind:t+1, \+ occluded_by(A, _):t+1.
lost_anywhere(A):t+1 := lost_anywhere(A):t, hidden(A):t+1, \+ occluded_by(A, _):t+1.

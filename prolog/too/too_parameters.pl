/*  too_parameters.pl -- the hand-written parameters of the theory of occlusion.

    Included by too.pl: the motion, carrying and occlusion constants (variances, reaches,
    heights).  The theories `anchoring learn-theory` writes have the ones they read fitted from
    the data instead (python/probanchor/app/motion_parameters.py).
*/

% ------------------------------------------------------------------ parameters
% Variances are per axis, in square metres; one step is one camera frame.
obs_var(0.0001).            % the measurement noise of a perceived position: (1 cm)^2
motion_var(0.0004).         % how far a perceived object moves in one frame: (2 cm)^2
reappear_var(0.0025).       % where a hidden object shows up again, around its belief: (5 cm)^2
lost_var(0.09).             % where an object lost while the camera saw nothing shows up again:
                            % (30 cm)^2 around its belief (it may have been moved anywhere)
follow_var(0.000004).       % jitter of a hidden object that follows its occluder: (2 mm)^2
wander_var(0.0001).         % how far a hidden object under nothing may move in a frame: (1 cm)^2
rest_var(0.0001).           % the same for one that was standing still as it vanished (as far:
                            % the hand-written theory does not tell the two apart)
moving_speed(0.004).        % a hidden object was moving as it vanished at 4 mm a frame or more
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
                            % (its centre: too.pl has no kind heights)
lift_margin(0.03).          % a carried object lifted 3 cm above where it stood was picked up ...
release_margin(0.02).       % ... and is put down when carried back within 2 cm of that height,
release_p(0.6).             % ... where the hand lets go of it with this probability per frame
grip_drop(0.02).            % what a hand holds is about 2 cm below its grip point
grip_rise(0.01).            % a hand rises when its grip goes up more than 1 cm in a frame

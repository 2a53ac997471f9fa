% The DDC system as a SWI-Prolog pack: prolog/ is the pack's library folder, so that with
% `swipl -p library=prolog` (or the pack attached) library(ddc) loads the DDC system (prolog/ddc.pl)
% and library(ddc/learn) the structure learner (prolog/ddc/learn.pl). The rest of prolog/ is
% the application's: the theories of occlusion (prolog/too*.pl and the parts they include, prolog/too/) and the world-model shell
% (prolog/shell/).
name(ddc).
version('0.1.0').
title('Dynamic Distributional Clauses: probabilistic logic programs over time, a particle filter and a structure learner').
keywords([probabilistic, logic, programming, particle, filter, distributional, clauses]).

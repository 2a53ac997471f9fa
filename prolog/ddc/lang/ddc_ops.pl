/** <module> The operators of the DC language

Part of the DDC system (ddc.pl is the module users load, and exports
them to its users).  The engine's and the learner's modules that read
or write DC terms import them from here.
*/

:- module(ddc_ops,
          [ op(700, xfx, ~),            % H ~ D: H has distribution D
            op(700, xfx, ~=),           % H ~= V: H's value is V
            op(1105, xfx, :=),          % Head := Body
            op(1105, xfx, <-),          % the paper's synonym of :=
            op(1150, xfx, pr)           % Clause pr N: a priority (ignored)
          ]).

/*  ddc_bridge.pl -- the Prolog side of the Python bridge (python/bridge/filter.py,
    python/bridge/frames.py).

    bridge.Filter calls these predicates through janus, one call per step or
    query, and bridge.frames one per frame file.  They parse the texts
    Python sends (in the operator context of module ddc), run the engine's
    filter predicates (filter_new/5, filter_step/4, ...) and the rules of
    the weights and resampling (ddc_weights.pl), turn errors into one-line
    messages and particle values into data janus maps onto Python values.
    Nothing here keeps state: the filter is the engine's, named by the text
    of its atom, the weights bridge.Filter's, handed in and back.
*/

:- module(ddc_bridge,
          [ bridge_new/9,               % +Program, +N, +Seed, +Share, +Threads, +Engine,
                                        % -Key, -Used, -Err
            bridge_step/5,              % +Key, +ObsTexts, +ActTexts, -LogWeights, -Err
            bridge_weighted_step/14,    % +Key, +ObsTexts, +ActTexts, +LogWeights0, +Threshold,
                                        % +Scheme, +Uniforms, -LogWeights, -Increment, -ESS,
                                        % -Infinite, -Drawn, -Ancestors, -Err
            bridge_undo/1,              % +Key
            bridge_resample/2,          % +Key, +Indices
            bridge_rename/5,            % +Key, +Olds, +News, +Indices, -Err
            bridge_time/2,              % +Key, -T
            bridge_free/1,              % +Key
            bridge_holds/4,             % +Key, +GoalText, -Flags, -Err
            bridge_values/4,            % +Key, +PairText, -Values, -Err
            bridge_numeric_rows/6,      % +Key, +PairText, -Width, -Floats, -Values, -Err
            bridge_rows_into/8,         % +Key, +PairText, +Address, +Capacity, -W, -F, -V, -Err
            bridge_indices_into/7,      % +Key, +PairText, +Atoms, +Address, +Capacity, -I, -Err
            bridge_frames/3             % +File, -Frames, -Err
          ]).

:- use_module(library(apply)).
:- use_module(library(error)).
:- use_module(library(pairs)).
:- use_module('../../ddc.pl', [ filter_new/5, filter_step/4, filter_undo/1, filter_resample/2,
                     filter_rename/3, filter_time/2, filter_engine/2, filter_free/1,
                     filter_holds/3, filter_values/4, filter_rows/6 ]).
:- use_module(ddc_filter, [filter_packed_rows/6, filter_packed_indices/5]).
:- use_module('../batch/ddc_batch_col', [col_floats_into/4, col_floats_list/2]).
:- use_module('../lang/ddc_nesting', [check_text_nesting/2]).
:- autoload(ddc_belief, [read_frame_file/2]).    % (loaded when a frame file is first read)
:- use_module(library(lists), [nth1/3]).
:- use_module(ddc_observation_types, [observation_type_error/4]).
:- use_module(ddc_weights).

/** <module> The Prolog side of the Python bridge

Python holds a filter as a Key, the text of the engine's filter atom (valid in every
thread, see filter_new/5).  Inputs arrive as texts (observations, actions, goals), parsed
here with term_string/3 in module ddc; a query's template and goal come as the text of one
term ddc_bridge_pair(Template, Goal), so that they share variables.

Predicates with an Err argument never raise: Err is "" on success, else Cause-Message (a
tuple in Python), Message one line (for a bad input item: `Kind I (Text): cause`, the text
cut to 200 characters) and Cause the kind of error it is (guarded/2), and the outputs are
empty.  The others raise the engine's errors (janus turns them into Python
exceptions).

Values go to Python as: numbers, atoms and strings as they are; lists item by item; comma
terms (A,B,C) as -(A,B,C), which janus makes a tuple; an unbound variable as "_"; any other
compound as its quoted text; a particle in which the goal has no solution as @(none).
*/

%   filter_of(+Key, -Filter): the engine's filter atom of a Key (a freed one
%   raises existence_error(ddc_filter, F) when used).
filter_of(Key, F) :-
    must_be(text, Key),
    atom_string(F, Key).

%!  bridge_new(+Program, +N, +Seed, +Share, +Threads, +Engine, -Key, -Used, -Err) is det.
%
%   A filter of Program's prior with N particles (filter_new/5 with the options
%   share(Share), threads(Threads), engine(Engine)).  Key is its atom, Used the engine that
%   steps it (batched or per_particle); both are `none` when Err is not "".
bridge_new(Program, N, Seed, Share, Threads, Engine, F, Used, Err) :-
    guarded(( filter_new(Program, N, Seed,
                         [share(Share), threads(Threads), engine(Engine)], F),
              filter_engine(F, Used) ), Err),
    ( var(Used) -> Used = none, F = none ; true ).

%!  bridge_step(+Key, +ObsTexts:list, +ActTexts:list, -LogWeights:list(float), -Err) is det.
%
%   One filter_step/4 with the observations and actions parsed from their texts; LogWeights
%   are the step's log weights as floats ([] when Err is not "").  A text that does not parse
%   or is not ground, or an observation whose value is of a type the program does not weigh
%   (ddc_observation_types.pl), is an error naming its kind (observation, action), its
%   1-based place and its text.
bridge_step(Key, ObsTexts, ActTexts, LW, Err) :-
    guarded(( text_step(Key, ObsTexts, ActTexts, _, LW0),
              maplist(to_float, LW0, LW)
            ), Err),
    ( var(LW) -> LW = [] ; true ).

%   text_step(+Key, +ObsTexts, +ActTexts, -F, -LogWeights): filter_step/4 of Key's filter F
%   with the observations and actions parsed and checked.
text_step(Key, ObsTexts, ActTexts, F, LW) :-
    filter_of(Key, F),
    parse_terms(observation, ObsTexts, Obs),
    parse_terms(action, ActTexts, Acts),
    check_observation_types(F, ObsTexts, Obs),
    filter_step(F, Obs, Acts, LW).

to_float(X, F) :- ( float(X) -> F = X ; F is float(X) ).

%!  bridge_weighted_step(+Key, +ObsTexts:list, +ActTexts:list, +LogWeights0:list(float),
%!                       +Threshold:float, +Scheme, +Uniforms:list(float),
%!                       -LogWeights:list(float), -Increment:float, -ESS:float,
%!                       -Infinite:boolean, -Drawn:integer, -Ancestors, -Err) is det.
%
%   One step of the weighted filter, by the rules of ddc_weights.pl: bridge_step/5, the
%   step's weighting from the normalised LogWeights0 the caller holds ([] for uniform
%   weights) by weights_update/6 (LogWeights the new ones, Increment the log of the step's
%   weighted mean likelihood, ESS the effective sample size, Infinite whether only
%   particles of infinite likelihood were kept), and, when resample_needed/3 says so with
%   Threshold, the resampling by Scheme: Ancestors are the indices resample_log_weights/5 picks
%   (0-based; `none` when not resampled), from the first Drawn of Uniforms (the caller's
%   draws: Drawn of them are used (resample_draws/3), 1 for systematic, N for the other
%   schemes), and LogWeights is [] (uniform).  When every particle gets weight 0
%   (Increment -inf) the step is undone (filter_undo/1) and LogWeights is [].  Outputs
%   are empty or none when Err is not "".
bridge_weighted_step(Key, ObsTexts, ActTexts, LW0, Th, Scheme, Us, LW, Inc, ESS, Inf, Drawn,
                     Ancestors, Err) :-
    guarded(( text_step(Key, ObsTexts, ActTexts, F, StepLW),
              length(StepLW, N),
              (   LW0 == [] -> weights_uniform(N, Uniform) ; Uniform = LW0 ),
              weights_update(Uniform, StepLW, LW1, Inc, ESS, Inf),
              (   Inc =:= -inf
              ->  filter_undo(F),
                  LW = [], Drawn = 0, Ancestors = none
              ;   resample_needed(ESS, Th, N)
              ->  resample_log_weights(Scheme, LW1, Us, Drawn, Ancestors),
                  filter_resample(F, Ancestors),
                  LW = []
              ;   LW = LW1, Drawn = 0, Ancestors = none
              )
            ), Err),
    (   var(LW)
    ->  LW = [], Inc = none, ESS = none, Inf = none, Drawn = 0, Ancestors = none
    ;   true
    ).

%!  bridge_undo(+Key) is det.
%
%   filter_undo/1: back to the particles before the last step.
bridge_undo(Key) :- filter_of(Key, F), filter_undo(F).

%!  bridge_resample(+Key, +Indices:list(integer)) is det.
%
%   filter_resample/2: particle i becomes a copy of particle Indices[i] (0-based).
bridge_resample(Key, Indices) :- filter_of(Key, F), filter_resample(F, Indices).

%!  bridge_rename(+Key, +Olds:list(text), +News:list(text), +Indices:list(integer), -Err)
%!      is det.
%
%   filter_rename/3 with the renaming Old-New of the atoms of the texts Olds and News (taken
%   as names, not parsed) in the particles Indices (1-based).
bridge_rename(Key, Olds, News, Indices, Err) :-
    guarded(( filter_of(Key, F),
              must_be(list(text), Olds), must_be(list(text), News),
              maplist(atom_string, OldAtoms, Olds),
              maplist(atom_string, NewAtoms, News),
              pairs_keys_values(Renaming, OldAtoms, NewAtoms),
              filter_rename(F, Renaming, Indices) ), Err).

%!  bridge_time(+Key, -T:integer) is det.
bridge_time(Key, T) :- filter_of(Key, F), filter_time(F, T).

%!  bridge_free(+Key) is det.
bridge_free(Key) :- filter_of(Key, F), filter_free(F).

%!  bridge_holds(+Key, +GoalText, -Flags:list, -Err) is det.
%
%   filter_holds/3 of the goal parsed from GoalText: per particle 1 if it holds, else 0.
bridge_holds(Key, GoalText, Flags, Err) :-
    guarded(( filter_of(Key, F), parse_goal(GoalText, Goal), filter_holds(F, Goal, Flags) ),
            Err),
    ( var(Flags) -> Flags = [] ; true ).

%!  bridge_values(+Key, +PairText, -Values:list, -Err) is det.
%
%   PairText is the text of ddc_bridge_pair(Template, Goal); Values holds per particle
%   Template at the first solution of Goal, as a Python value, or @(none).  (The template
%   is wrapped: filter_values/4 gives the atom none for a particle without a solution,
%   which must not be taken for a value none.)
bridge_values(Key, PairText, Values, Err) :-
    guarded(( filter_of(Key, F), parse_goal(PairText, ddc_bridge_pair(Template, Goal)),
              filter_values(F, value(Template), Goal, Values0),
              maplist(py_solution, Values0, Values) ), Err),
    ( var(Values) -> Values = [] ; true ).

%!  bridge_numeric_rows(+Key, +PairText, -Width, -Floats:list, -Values:list, -Err) is det.
%
%   The values of bridge_values/4 as N rows of Width floats (NaN where the goal has no
%   solution) when every value is a number or a tuple of Width numbers (Values []); else
%   Width 0 and the Values of bridge_values/4 (filter_rows/6).
bridge_numeric_rows(Key, PairText, Width, Floats, Values, Err) :-
    guarded(( filter_of(Key, F), parse_goal(PairText, ddc_bridge_pair(Template, Goal)),
              filter_rows(F, Template, Goal, Width, Floats, Values0),
              maplist(py_solution, Values0, Values) ), Err),
    ( var(Width) -> Width = 0, Floats = [], Values = [] ; true ).

%!  bridge_rows_into(+Key, +PairText, +Address, +Capacity, -Width, -Floats, -Values:list,
%!                   -Err) is det.
%
%   bridge_numeric_rows/6, with the floats, where the engine reads them straight from
%   its columns (the batched engine with its column library), copied into the memory at
%   Address that holds Capacity doubles (a numpy array of the caller's: Floats is then
%   their number, an integer) instead of a list of floats that janus converts one by one
%   (10,000 particles' positions: 30,000 floats).  Floats is a list where they are not
%   copied (no library, other values, or more than Capacity of them).
bridge_rows_into(Key, PairText, Address, Capacity, Width, Floats, Values, Err) :-
    guarded(( must_be(integer, Address), must_be(nonneg, Capacity),
              filter_of(Key, F), parse_goal(PairText, ddc_bridge_pair(Template, Goal)),
              filter_packed_rows(F, Template, Goal, Width, Rows, Values0),
              rows_into(Rows, Address, Capacity, Floats),
              maplist(py_solution, Values0, Values) ), Err),
    ( var(Width) -> Width = 0, Floats = [], Values = [] ; true ).

%!  bridge_indices_into(+Key, +PairText, +Atoms:list(text), +Address, +Capacity,
%!                      -Indices, -Err) is det.
%
%   filter_packed_indices/5 of ddc_bridge_pair(Template, Goal) parsed from
%   PairText and the atoms of the texts Atoms (taken as names): where the
%   engine reads them from its columns, copied as doubles into the memory
%   at Address that holds Capacity of them (NaN for -1; Indices their
%   number), else Indices a list of integers.
bridge_indices_into(Key, PairText, Texts, Address, Capacity, Indices, Err) :-
    guarded(( must_be(integer, Address), must_be(nonneg, Capacity),
              must_be(list(text), Texts), maplist(atom_string, Atoms, Texts),
              filter_of(Key, F), parse_goal(PairText, ddc_bridge_pair(Template, Goal)),
              filter_packed_indices(F, Template, Goal, Atoms, Packed),
              rows_into(Packed, Address, Capacity, Indices) ), Err),
    ( var(Indices) -> Indices = [] ; true ).

rows_into(Rows, Address, Capacity, Floats) :-
    (   is_list(Rows) -> Floats = Rows
    ;   col_floats_into(Rows, Address, Capacity, N) -> Floats = N
    ;   col_floats_list(Rows, Floats)
    ).

%!  bridge_frames(+File, -Frames:list, -Err) is det.
%
%   The frames of a frame file (JSON Lines, the format of `ddc filter`), read by
%   ddc_belief's read_frame_file/2, the one reader of the format: Frames holds per frame
%   -(Line, ObservationTexts, ActionTexts) (a tuple in Python), each term written back as
%   text that term_string/3 in module ddc reads as the same term.  A bad line gives
%   Frames [] and Err "File:Line: cause".
bridge_frames(File, Frames, Err) :-
    guarded(( read_frame_file(File, Frames0),
              maplist(frame_texts, Frames0, Frames) ), Err),
    ( var(Frames) -> Frames = [] ; true ).

frame_texts(frame(Line, Obs, Acts), -(Line, ObsTexts, ActTexts)) :-
    maplist(term_text, Obs, ObsTexts),
    maplist(term_text, Acts, ActTexts).

%   term_text(+Term, -Text): Text reads back (in module ddc) as Term.
term_text(Term, Text) :-
    format(string(Text), "~W",
           [ Term, [ quoted(true), module(ddc), spacing(next_argument),
                     numbervars(false), portray(false), ignore_ops(false) ] ]).

		 /*******************************
		 *            ERRORS            *
		 *******************************/

%   guarded(:Goal, -Err): Goal once; Err "" if it succeeded, else Cause-Text (a tuple in
%   Python): Text the message of the error it raised, Cause the name of its formal term
%   (ddc, existence_error, ...; bad_input for a text that does not parse, is not ground or
%   is of a type the program does not weigh; other for anything else), from which Python
%   picks the class of the error (python/bridge/errors.py).
guarded(Goal, Err) :-
    catch((Goal, Err = ""), E,
          ( error_text(E, Msg), bridge_error(E, Msg, Text), error_cause(E, Cause),
            Err = Cause-Text )).

error_cause(bridge(_, _, _, _), bad_input) :- !.
error_cause(error(Formal, _), Cause) :- callable(Formal), !, functor(Formal, Cause, _).
error_cause(_, other).

%   error_text(+Error, -Text): the message SWI-Prolog prints for Error, on one line.
error_text(bridge(_, _, _, Msg), Msg) :- !.
error_text(E, S) :-
    catch(( '$messages':translate_message(E, Lines, []),
            with_output_to(string(S0), print_message_lines(current_output, '', Lines)),
            split_string(S0, "", "\n ", [S])
          ), _, fail), !.
error_text(E, S) :- format(string(S), "~q", [E]).

bridge_error(bridge(goal, _, Text0, Msg), _, Err) :- !,
    shown_text(Text0, Text),
    format(string(Err), "goal ~w: ~w", [Text, Msg]).
bridge_error(bridge(Kind, I, Text0, Msg), _, Err) :- !,
    shown_text(Text0, Text),
    format(string(Err), "~w ~w (~w): ~w", [Kind, I, Text, Msg]).
bridge_error(_, Msg, Msg).

%   shown_text(+Text, -Shown): a text as an error message shows it (at most 200 characters)
shown_text(Text, Shown) :-
    string_length(Text, N),
    (   N =< 200 -> Shown = Text
    ;   sub_string(Text, 0, 120, _, Head), sub_string(Text, _, 40, 0, Tail),
        format(string(Shown), "~w ... ~w, ~D characters", [Head, Tail, N])
    ).

		 /*******************************
		 *        PARSING TEXTS         *
		 *******************************/

%   parse_terms(+Kind, +Texts, -Terms): Texts parsed, each ground, else bridge(Kind, I,
%   Text, Message) for the first that is not.
parse_terms(Kind, Texts, Terms) :-
    must_be(list, Texts),
    foldl(parse_term(Kind), Texts, Terms, 1, _).

parse_term(Kind, Text, Term, I, I1) :-
    I1 is I + 1,
    catch(( check_text_nesting(Text, nowhere),
            term_string(Term, Text, [module(ddc)]) ), E,
          ( error_text(E, Msg0), clean(Msg0, Msg), throw(bridge(Kind, I, Text, Msg)) )),
    (   ground(Term) -> true
    ;   throw(bridge(Kind, I, Text, "not ground (observations and actions must be)"))
    ).

%   check_observation_types(+F, +Texts, +Obs): bridge(observation, I, Text, Message) for
%   the first observation whose value is of a type no clause of F's program weighs
%   (ddc_observation_types.pl).
check_observation_types(F, Texts, Obs) :-
    (   observation_type_error(F, Obs, I, Message)
    ->  nth1(I, Texts, Text),
        throw(bridge(observation, I, Text, Message))
    ;   true
    ).

%   clean(+Message, -FirstLine)
clean(Msg0, Msg) :- split_string(Msg0, "\n", " ", [Msg|_]), !.
clean(Msg, Msg).

parse_goal(Text, Goal) :-
    catch(( check_text_nesting(Text, nowhere),
            term_string(Goal, Text, [module(ddc)]) ), E,
          ( error_text(E, Msg0), clean(Msg0, Msg), throw(bridge(goal, "", Text, Msg)) )).

		 /*******************************
		 *        VALUES TO PYTHON      *
		 *******************************/

py_solution(none, @(none)).
py_solution(value(V), P) :- py_value(V, P).

%   py_value(+Value, -PythonValue): see the module comment.
py_value(V, "_") :- var(V), !.
py_value(V, V) :- number(V), !.
py_value(V, V) :- atom(V), !.
py_value(V, V) :- string(V), !.
py_value(V, P) :- is_list(V), !, maplist(py_value, V, P).
py_value((A, B), P) :- !, comma_items((A, B), Items), maplist(py_value, Items, Ps), P =.. [-|Ps].
py_value(V, S) :- format(string(S), "~q", [V]).

comma_items((A, B), [A|Rest]) :- !, comma_items(B, Rest).
comma_items(A, [A]).

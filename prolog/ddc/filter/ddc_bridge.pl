/*  ddc_bridge.pl -- the Prolog side of the Python bridge (python/bridge/filter.py,
    python/bridge/frames.py).

    bridge.Filter calls these predicates through janus, one call per step or
    query, and bridge.frames one per frame file.  They parse the texts
    Python sends (in the operator context of module ddc), run the engine's
    filter predicates (filter_new/5, filter_step/4, ...) and the rules of
    the weights and resampling (ddc_weights.pl), and turn particle values
    into data janus maps onto Python values.  Errors are raised as ISO error
    terms, which the adapter (python/bridge/prolog.py) turns into Python
    exceptions.  Nothing here keeps state: the filter is the engine's, named
    by the text of its atom, the weights bridge.Filter's, handed in and back.
*/

:- module(ddc_bridge,
          [ bridge_new/8,               % +Program, +N, +Seed, +Share, +Threads, +Engine,
                                        % -Key, -Used
            bridge_weighted_step/13,    % +Key, +ObsTexts, +ActTexts, +LogWeights0, +Threshold,
                                        % +Scheme, +Uniforms, -LogWeights, -Increment, -ESS,
                                        % -Infinite, -Drawn, -Ancestors
            bridge_weighted_step/15,    % ... as /13, with +Strata, +Keep after +Scheme
            bridge_undo/1,              % +Key
            bridge_rename/4,            % +Key, +Olds, +News, +Indices
            bridge_time/2,              % +Key, -T
            bridge_free/1,              % +Key
            bridge_holds/3,             % +Key, +GoalText, -Flags
            bridge_values/3,            % +Key, +PairText, -Values
            bridge_numeric_rows/5,      % +Key, +PairText, -Width, -Floats, -Values
            bridge_rows_into/7,         % +Key, +PairText, +Address, +Capacity, -W, -F, -V
            bridge_indices_into/6,      % +Key, +PairText, +Atoms, +Address, +Capacity, -I
            bridge_frames/2,            % +File, -Frames
            bridge_with_includes/2       % +File, -Files
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
:- use_module('../lang/ddc_source', [source_file/3, source_terms/3]).
:- autoload(ddc_belief, [read_frame_file/2]).    % (loaded when a frame file is first read)
:- use_module(library(lists), [member/2, nth1/3, list_to_set/2]).
:- use_module(ddc_observation_types, [observation_type_error/4]).
:- use_module(ddc_weights).

/** <module> The Prolog side of the Python bridge

Python holds a filter as a Key, the text of the engine's filter atom (valid in every
thread, see filter_new/5).  Inputs arrive as texts (observations, actions, goals), parsed
here with term_string/3 in module ddc; a query's template and goal come as the text of one
term ddc_bridge_pair(Template, Goal), so that they share variables.

Errors are ISO error terms.  The engine's own (a program's error(ddc(Cause, File:Line), _),
existence_error(ddc_filter, F) for a filter freed, ...) pass as they are raised.  A bad
input text raises error(Formal, context(ddc_bridge:PI, Message)), PI the bridge predicate
called and Message one line naming the item, `Kind I (Text): cause` (the text cut to 200
characters; `goal Text: cause` for a query's goal): Formal is syntax_error(What) for a
text that does not parse, instantiation_error for an observation or action that is not
ground, type_error(weighed_observation, Observation) for an observation whose value is of
a type the program does not weigh.  Such an error prints as its Message alone
(prolog:message//1 below), and that is the message the Python exception carries.

Values go to Python as: numbers, atoms and strings as they are; lists item by item; comma
terms (A,B,C) as -(A,B,C), which janus makes a tuple; an unbound variable as "_"; any other
compound as its quoted text; a particle in which the goal has no solution as @(none).
*/

%   filter_of(+Key, -Filter): the engine's filter atom of a Key (a freed one
%   raises existence_error(ddc_filter, F) when used).
filter_of(Key, F) :-
    must_be(text, Key),
    atom_string(F, Key).

%!  bridge_new(+Program, +N, +Seed, +Share, +Threads, +Engine, -Key, -Used) is det.
%
%   A filter of Program's prior with N particles (filter_new/5 with the options
%   share(Share), threads(Threads), engine(Engine)).  Key is its atom, Used the engine that
%   steps it (batched or per_particle).
%
%   @error as filter_new/5: syntax_error(What) for a program that does not parse,
%          ddc(Cause, File:Line) for a clause the DDC system refuses, existence_error for a
%          file that does not exist, ...
bridge_new(Program, N, Seed, Share, Threads, Engine, F, Used) :-
    filter_new(Program, N, Seed, [share(Share), threads(Threads), engine(Engine)], F),
    filter_engine(F, Used).

%   text_step(+PI, +Key, +ObsTexts, +ActTexts, -F, -LogWeights): filter_step/4 of Key's
%   filter F with the observations and actions parsed and checked (errors naming PI).
text_step(PI, Key, ObsTexts, ActTexts, F, LW) :-
    filter_of(Key, F),
    parse_terms(PI, observation, ObsTexts, Obs),
    parse_terms(PI, action, ActTexts, Acts),
    check_observation_types(PI, F, ObsTexts, Obs),
    filter_step(F, Obs, Acts, LW).

%!  bridge_weighted_step(+Key, +ObsTexts:list, +ActTexts:list, +LogWeights0:list(float),
%!                       +Threshold:float, +Scheme, +Uniforms:list(float),
%!                       -LogWeights:list(float), -Increment:float, -ESS:float,
%!                       -Infinite:boolean, -Drawn:integer, -Ancestors) is det.
%
%   One step of the weighted filter, by the rules of ddc_weights.pl: filter_step/4 with the
%   observations and actions parsed from their texts, the step's weighting from the
%   normalised LogWeights0 the caller holds ([] for uniform weights) by weights_update/6
%   (LogWeights the new ones, Increment the log of the step's weighted mean likelihood, ESS
%   the effective sample size, Infinite whether only particles of infinite likelihood were
%   kept), and, when resample_needed/3 says so with Threshold, the resampling by Scheme:
%   Ancestors are the indices resample_log_weights/5 picks (0-based; `none` when not
%   resampled), from the first Drawn of Uniforms (the caller's draws: Drawn of them are
%   used (resample_draws/3), 1 for systematic, N for the other schemes), and LogWeights is
%   [] (uniform).  When every particle gets weight 0 (Increment -inf) the step is undone
%   (filter_undo/1) and LogWeights is [].
%
%   @error syntax_error(What), context(ddc_bridge:bridge_weighted_step/13, Message) for
%          an observation or action text that does not parse, Message
%          `observation I (Text): cause` (or `action I ...`).
%   @error instantiation_error (same context) for one that is not ground.
%   @error type_error(weighed_observation, Observation) (same context) for an observation
%          whose value is of a type no clause of the program weighs
%          (ddc_observation_types.pl).
%   @error existence_error(ddc_filter, F) for a filter freed; the engine's errors of a step
%          (a clause that misbehaves: ddc(Cause, File:Line)).
bridge_weighted_step(Key, ObsTexts, ActTexts, LW0, Th, Scheme, Us, LW, Inc, ESS, Inf, Drawn,
                     Ancestors) :-
    weighted_step(bridge_weighted_step/13, Key, ObsTexts, ActTexts, LW0, Th, Scheme, [], 1, Us,
                  LW, Inc, ESS, Inf, Drawn, Ancestors).

%!  bridge_weighted_step(+Key, +ObsTexts:list, +ActTexts:list, +LogWeights0:list(float),
%!                       +Threshold:float, +Scheme, +Strata:list(integer), +Keep:integer,
%!                       +Uniforms:list(float), -LogWeights:list(float), -Increment:float,
%!                       -ESS:float, -Infinite:boolean, -Drawn:integer, -Ancestors) is det.
%
%   bridge_weighted_step/13, but for Strata other than []: a resampling is then
%   resample_preserving/6's (each stratum of the particles, one integer per particle, is
%   resampled on its own and keeps its mass with at least Keep particles; Drawn 1), and
%   LogWeights are the resampled particles' weights (not uniform).
%
%   @error as bridge_weighted_step/13 (context bridge_weighted_step/15);
%          domain_error(same_length(N), Strata) for Strata of another length than the
%          particles; type_error for Strata not a list of integers or Keep not a positive
%          integer.
bridge_weighted_step(Key, ObsTexts, ActTexts, LW0, Th, Scheme, Strata, Keep, Us, LW, Inc, ESS,
                     Inf, Drawn, Ancestors) :-
    must_be(list(integer), Strata),
    must_be(positive_integer, Keep),
    weighted_step(bridge_weighted_step/15, Key, ObsTexts, ActTexts, LW0, Th, Scheme, Strata,
                  Keep, Us, LW, Inc, ESS, Inf, Drawn, Ancestors).

weighted_step(PI, Key, ObsTexts, ActTexts, LW0, Th, Scheme, Strata, Keep, Us, LW, Inc, ESS, Inf,
              Drawn, Ancestors) :-
    text_step(PI, Key, ObsTexts, ActTexts, F, StepLW),
    length(StepLW, N),
    (   LW0 == [] -> weights_uniform(N, Uniform) ; Uniform = LW0 ),
    weights_update(Uniform, StepLW, LW1, Inc, ESS, Inf),
    (   Inc =:= -inf
    ->  filter_undo(F),
        LW = [], Drawn = 0, Ancestors = none
    ;   resample_needed(ESS, Th, N)
    ->  (   Strata == []
        ->  resample_log_weights(Scheme, LW1, Us, Drawn, Ancestors),
            LW = []
        ;   resample_preserving(LW1, Strata, Keep, Us, Ancestors, LW),
            Drawn = 1
        ),
        filter_resample(F, Ancestors)
    ;   LW = LW1, Drawn = 0, Ancestors = none
    ).

%!  bridge_undo(+Key) is det.
%
%   filter_undo/1: back to the particles before the last step.
%
%   @error permission_error as filter_undo/1 (no step to undo).
bridge_undo(Key) :- filter_of(Key, F), filter_undo(F).

%!  bridge_rename(+Key, +Olds:list(text), +News:list(text), +Indices:list(integer)) is det.
%
%   filter_rename/3 with the renaming Old-New of the atoms of the texts Olds and News (taken
%   as names, not parsed) in the particles Indices (1-based).
%
%   @error as filter_rename/3: domain_error for a renaming that is not a permutation or an
%          index outside 1..N; type_error for names that are not texts.
bridge_rename(Key, Olds, News, Indices) :-
    filter_of(Key, F),
    must_be(list(text), Olds), must_be(list(text), News),
    maplist(atom_string, OldAtoms, Olds),
    maplist(atom_string, NewAtoms, News),
    pairs_keys_values(Renaming, OldAtoms, NewAtoms),
    filter_rename(F, Renaming, Indices).

%!  bridge_time(+Key, -T:integer) is det.
bridge_time(Key, T) :- filter_of(Key, F), filter_time(F, T).

%!  bridge_free(+Key) is det.
bridge_free(Key) :- filter_of(Key, F), filter_free(F).

%!  bridge_holds(+Key, +GoalText, -Flags:list) is det.
%
%   filter_holds/3 of the goal parsed from GoalText: per particle 1 if it holds, else 0.
%
%   @error syntax_error(What), context(ddc_bridge:bridge_holds/3, Message) for a goal
%          text that does not parse, Message `goal Text: cause`; the errors of the goal as
%          it runs.
bridge_holds(Key, GoalText, Flags) :-
    filter_of(Key, F),
    parse_goal(bridge_holds/3, GoalText, Goal),
    filter_holds(F, Goal, Flags).

%!  bridge_values(+Key, +PairText, -Values:list) is det.
%
%   PairText is the text of ddc_bridge_pair(Template, Goal); Values holds per particle
%   Template at the first solution of Goal, as a Python value, or @(none).  (The template
%   is wrapped: filter_values/4 gives the atom none for a particle without a solution,
%   which must not be taken for a value none.)
%
%   @error syntax_error(What), context(ddc_bridge:bridge_values/3, Message) for a text
%          that does not parse (as bridge_holds/3).
bridge_values(Key, PairText, Values) :-
    filter_of(Key, F),
    parse_goal(bridge_values/3, PairText, ddc_bridge_pair(Template, Goal)),
    filter_values(F, value(Template), Goal, Values0),
    maplist(py_solution, Values0, Values).

%!  bridge_numeric_rows(+Key, +PairText, -Width, -Floats:list, -Values:list) is det.
%
%   The values of bridge_values/3 as N rows of Width floats (NaN where the goal has no
%   solution) when every value is a number or a tuple of Width numbers (Values []); else
%   Width 0 and the Values of bridge_values/3 (filter_rows/6).
%
%   @error as bridge_values/3.
bridge_numeric_rows(Key, PairText, Width, Floats, Values) :-
    filter_of(Key, F),
    parse_goal(bridge_numeric_rows/5, PairText, ddc_bridge_pair(Template, Goal)),
    filter_rows(F, Template, Goal, Width, Floats, Values0),
    maplist(py_solution, Values0, Values).

%!  bridge_rows_into(+Key, +PairText, +Address, +Capacity, -Width, -Floats, -Values:list)
%!      is det.
%
%   bridge_numeric_rows/5, with the floats, where the engine reads them straight from
%   its columns (the batched engine with its column library), copied into the memory at
%   Address that holds Capacity doubles (a numpy array of the caller's: Floats is then
%   their number, an integer) instead of a list of floats that janus converts one by one
%   (10,000 particles' positions: 30,000 floats).  Floats is a list where they are not
%   copied (no library, other values, or more than Capacity of them).
%
%   @error type_error(integer, Address), type_error(nonneg, Capacity); as bridge_values/3.
bridge_rows_into(Key, PairText, Address, Capacity, Width, Floats, Values) :-
    must_be(integer, Address), must_be(nonneg, Capacity),
    filter_of(Key, F),
    parse_goal(bridge_rows_into/7, PairText, ddc_bridge_pair(Template, Goal)),
    filter_packed_rows(F, Template, Goal, Width, Rows, Values0),
    rows_into(Rows, Address, Capacity, Floats),
    maplist(py_solution, Values0, Values).

%!  bridge_indices_into(+Key, +PairText, +Atoms:list(text), +Address, +Capacity,
%!                      -Indices) is det.
%
%   filter_packed_indices/5 of ddc_bridge_pair(Template, Goal) parsed from
%   PairText and the atoms of the texts Atoms (taken as names): where the
%   engine reads them from its columns, copied as doubles into the memory
%   at Address that holds Capacity of them (NaN for -1; Indices their
%   number), else Indices a list of integers.
%
%   @error as bridge_rows_into/7; type_error(list(text), Atoms).
bridge_indices_into(Key, PairText, Texts, Address, Capacity, Indices) :-
    must_be(integer, Address), must_be(nonneg, Capacity),
    must_be(list(text), Texts), maplist(atom_string, Atoms, Texts),
    filter_of(Key, F),
    parse_goal(bridge_indices_into/6, PairText, ddc_bridge_pair(Template, Goal)),
    filter_packed_indices(F, Template, Goal, Atoms, Packed),
    rows_into(Packed, Address, Capacity, Indices).

rows_into(Rows, Address, Capacity, Floats) :-
    (   is_list(Rows) -> Floats = Rows
    ;   col_floats_into(Rows, Address, Capacity, N) -> Floats = N
    ;   col_floats_list(Rows, Floats)
    ).

%!  bridge_frames(+File, -Frames:list) is det.
%
%   The frames of a frame file (JSON Lines, the format of `ddc filter`), read by
%   ddc_belief's read_frame_file/2, the one reader of the format: Frames holds per frame
%   -(Line, ObservationTexts, ActionTexts) (a tuple in Python), each term written back as
%   text that term_string/3 in module ddc reads as the same term.
%
%   @error ddc_belief(frame(File, Line, Cause)) for the first bad line (its message
%          `File:Line: cause`); existence_error(source_sink, File) for a file that does not
%          exist.
bridge_frames(File, Frames) :-
    read_frame_file(File, Frames0),
    maplist(frame_texts, Frames0, Frames).

frame_texts(frame(Line, Obs, Acts), -(Line, ObsTexts, ActTexts)) :-
    maplist(term_text, Obs, ObsTexts),
    maplist(term_text, Acts, ActTexts).

%!  bridge_with_includes(+File, -Files:list(atom)) is det.
%
%   The absolute names of the DC file File and of every file it includes (`:- include/1`,
%   transitively, each found relative to the file that includes it), in the order the one
%   reader of DC files (ddc_source.pl) reads them, File first.  An included file that holds
%   no clause or directive (comments only) is not among them: it changes nothing read.
%
%   @error as source_file/3 and source_terms/3: existence_error(source_sink, Spec) for a
%          file (or an included file) that does not exist, syntax_error(Message) naming
%          File:Line, permission_error(include, source_sink, F) for a file that includes
%          itself.
bridge_with_includes(Spec, Files) :-
    source_file(Spec, [], File),
    source_terms(File, [module(ddc), variable_names(false)], Terms),
    findall(F, member(src(_, _, F, _), Terms), Fs),
    list_to_set([File|Fs], Files).

%   term_text(+Term, -Text): Text reads back (in module ddc) as Term.
term_text(Term, Text) :-
    format(string(Text), "~W",
           [ Term, [ quoted(true), module(ddc), spacing(next_argument),
                     numbervars(false), portray(false), ignore_ops(false) ] ]).

		 /*******************************
		 *            ERRORS            *
		 *******************************/

%   input_error(+PI, +Formal, +Kind, +I, +Text, +Cause): raise the ISO error of a bad input
%   item: error(Formal, context(ddc_bridge:PI, Message)), Message `Kind I (Text): Cause`
%   (`goal Text: Cause` for a goal), the text cut to 200 characters.
input_error(PI, Formal, goal, _, Text0, Cause) :- !,
    shown_text(Text0, Text),
    format(string(Message), "goal ~w: ~w", [Text, Cause]),
    throw(error(Formal, context(ddc_bridge:PI, Message))).
input_error(PI, Formal, Kind, I, Text0, Cause) :-
    shown_text(Text0, Text),
    format(string(Message), "~w ~w (~w): ~w", [Kind, I, Text, Cause]),
    throw(error(Formal, context(ddc_bridge:PI, Message))).

:- multifile prolog:message//1.

%   A bad input item's error prints as its message alone: it names the item and the cause.
prolog:message(error(_, context(ddc_bridge:_, Message))) -->
    { string(Message) }, !,
    [ '~w'-[Message] ].

%   error_text(+Error, -Text): the message SWI-Prolog prints for Error, on one line.
error_text(E, S) :-
    catch(( '$messages':translate_message(E, Lines, []),
            with_output_to(string(S0), print_message_lines(current_output, '', Lines)),
            split_string(S0, "", "\n ", [S])
          ), _, fail), !.
error_text(E, S) :- format(string(S), "~q", [E]).

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

%   parse_terms(+PI, +Kind, +Texts, -Terms): Texts parsed, each ground, else the
%   input_error/6 of the first that is not.
parse_terms(PI, Kind, Texts, Terms) :-
    must_be(list, Texts),
    foldl(parse_term(PI, Kind), Texts, Terms, 1, _).

parse_term(PI, Kind, Text, Term, I, I1) :-
    I1 is I + 1,
    catch(( check_text_nesting(Text, nowhere),
            term_string(Term, Text, [module(ddc)]) ), E,
          unparsed(E, PI, Kind, I, Text)),
    (   ground(Term) -> true
    ;   input_error(PI, instantiation_error, Kind, I, Text,
                    "not ground (observations and actions must be)")
    ).

%   unparsed(+Error, +PI, +Kind, +I, +Text): the input_error/6 of a text that did not parse
%   (Error raised by the parser or by check_text_nesting/2): syntax_error(What), What the
%   parser's, or the ddc cause (too_deep(Max)) of a text nested too deep.
unparsed(E, PI, Kind, I, Text) :-
    error_text(E, Msg0), clean(Msg0, Msg),
    (   E = error(syntax_error(What), _) -> true
    ;   E = error(ddc(What, _), _) -> true
    ;   What = E
    ),
    input_error(PI, syntax_error(What), Kind, I, Text, Msg).

%   check_observation_types(+PI, +F, +Texts, +Obs): the input_error/6
%   (type_error(weighed_observation, Observation)) of the first observation whose value is
%   of a type no clause of F's program weighs (ddc_observation_types.pl).
check_observation_types(PI, F, Texts, Obs) :-
    (   observation_type_error(F, Obs, I, Message)
    ->  nth1(I, Texts, Text), nth1(I, Obs, Ob),
        input_error(PI, type_error(weighed_observation, Ob), observation, I, Text, Message)
    ;   true
    ).

%   clean(+Message, -FirstLine)
clean(Msg0, Msg) :- split_string(Msg0, "\n", " ", [Msg|_]), !.
clean(Msg, Msg).

parse_goal(PI, Text, Goal) :-
    catch(( check_text_nesting(Text, nowhere),
            term_string(Goal, Text, [module(ddc)]) ), E,
          unparsed(E, PI, goal, "", Text)).

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

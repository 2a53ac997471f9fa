/*  ddc_belief.pl -- the particle filter's belief, weighted, for swipl users.

    The filter predicates of ddc.pl (filter_new/5, filter_step/4, ...) hold
    the particles and return each step's log weights; the weights, the
    effective sample size, the resampling and the running log-likelihood
    are kept by the caller, by the rules of ddc_weights.pl (which the
    Python bridge's bridge.Filter calls too).  This module keeps them in
    Prolog, so that a program can be filtered and its belief queried from
    swipl:

        swipl prolog/ddc/filter/ddc_belief.pl
        ?- belief_new('prolog/examples/filter/pit_world.pl',
                      [particles(2000), seed(5)], B),
           belief_run(B, 'prolog/examples/filter/pit_world.jsonl'),
           belief_probability(B, maze(1,1):t ~= free, P),
           belief_distribution(B, maze(2,0):t, D).

    (The resampling's uniforms come from a Prolog random stream here, from
    a numpy Generator in bridge.Filter: the same seed gives the same
    answers within Prolog, bit for bit, not the same answers as the Python
    side.)
*/

:- module(ddc_belief,
          [ belief_new/3,                % +ProgramFile, +Options, -Belief
            belief_step/3,               % +Belief, +Observations, +Actions
            belief_step/4,               % +Belief, +Observations, +Actions, -Step
            belief_run/2,                % +Belief, +FramesFile
            belief_run/3,                % +Belief, +FramesFile, :OnStep
            belief_probability/3,        % +Belief, +Goal, -P
            belief_distribution/3,       % +Belief, +Term, -Dist
            belief_distribution/4,       % +Belief, +Template, +Goal, -Dist
            belief_mean/4,               % +Belief, +Term, -Mean, -Cov
            belief_samples/3,            % +Belief, +Term, -Samples
            belief_weights/2,            % +Belief, -Weights
            belief_ess/2,                % +Belief, -ESS
            belief_time/2,               % +Belief, -T
            belief_log_likelihood/2,     % +Belief, -LogLikelihood
            belief_zero_weight_events/2, % +Belief, -Count
            belief_filter/2,             % +Belief, -Filter
            belief_free/1,               % +Belief
            read_frame_file/2,           % +File, -Frames
            resample_indices/4           % +Scheme, +Weights, +Uniforms, -Indices
          ]).
:- reexport('../../ddc.pl').

:- use_module(library(apply)).
:- use_module(library(lists)).
:- use_module(library(option)).
:- use_module(library(error)).
:- use_module(library(pairs)).
:- use_module(library(readutil)).
:- use_module(library(http/json)).
:- use_module('../lang/ddc_nesting').
:- use_module('../runtime/ddc_pool', [with_random_stream/3]).
:- use_module(ddc_weights).

:- meta_predicate belief_run(+, +, 1).

/** <module> Weighted particle belief over a DDC filter

A Belief is belief(Key); its state (the filter, the normalised log
weights, the running log-likelihood, the zero-weight events, the
resampling options and random stream) is a global variable of the calling
thread named Key (the filter inside it, as any filter, may be called from
any thread: see filter_new/5), and goes with belief_free/1.  A step or query that raises an error leaves the belief as
it was.
*/

%!  belief_new(+ProgramFile, +Options, -Belief) is det.
%
%   Loads ProgramFile and makes a filter of its prior.  Options:
%     - particles(N): number of particles (default 1000)
%     - seed(S): the seed of the particles and of the resampling (default 0)
%     - threads(K): Prolog threads that step the particles (default 1)
%     - resample_threshold(F): resample when the effective sample size
%       falls below F*N (default 0.9)
%     - resampling(Scheme): systematic (default), multinomial or residual
%     - share(Bool): compute the values the particles agree on once
%       (default true; see filter_new/5)
%     - engine(E): auto (default), batched or per_particle (see
%       filter_new/5)
belief_new(File, Options, belief(Key)) :-
    option(particles(N), Options, 1000),
    option(seed(Seed), Options, 0),
    option(threads(K), Options, 1),
    option(resample_threshold(Th), Options, 0.9),
    option(resampling(Scheme), Options, systematic),
    option(share(Share), Options, true),
    option(engine(Engine), Options, auto),
    must_be(positive_integer, N),
    must_be(integer, Seed),
    must_be(between(0.0, 1.0), Th),
    must_be(oneof([systematic, multinomial, residual]), Scheme),
    filter_new(File, N, Seed, [threads(K), share(Share), engine(Engine)], F),
    weights_uniform(N, LWs),
    resampling_stream(Seed, R),
    gensym('$ddc_belief_', Key),
    nb_setval(Key, belief(F, N, LWs, 0.0, 0, Th, Scheme, R, 0)).

%   The resampling draws come from a stream of their own, seeded from Seed
%   but not equal to the particles' stream.
resampling_stream(Seed, R) :-
    term_hash(resampling(Seed), S),
    with_random_stream(seed(S), true, R).

state(belief(Key), S) :-
    (   atom(Key), nb_current(Key, S0), S0 = belief(_, _, _, _, _, _, _, _, _)
    ->  S = S0
    ;   throw(error(existence_error(belief, belief(Key)), _))
    ).

%!  belief_free(+Belief) is det.
%
%   Frees the belief's filter and state.
belief_free(B) :-
    state(B, belief(F, _, _, _, _, _, _, _, _)),
    filter_free(F),
    B = belief(Key),
    nb_delete(Key).

%!  belief_step(+Belief, +Observations, +Actions) is det.
%!  belief_step(+Belief, +Observations, +Actions, -Step) is det.
%
%   One filter step (filter_step/4) with the observations (`h ~= v` and
%   plain facts) and actions of time t+1, then, by the rules of
%   ddc_weights.pl (weights_update/6): the log weights become the
%   normalised sum of the old ones and the step's (NaN counts as -inf);
%   the log of their weighted mean likelihood is added to the
%   log-likelihood; if the effective sample size falls below the
%   threshold the particles are resampled (resample_indices/4, N uniforms
%   drawn from the belief's stream) and the weights made uniform.  If every particle gets weight 0, the step is undone, the
%   weights are made uniform, a warning is printed and the zero-weight
%   count goes up: the time does not advance.  Step is a dict step{time,
%   frame, ess, resampled, log_likelihood, zero_weight} (log_likelihood:
%   this step's increment, -inf for a zero-weight step).
belief_step(B, Obs, Acts) :-
    belief_step(B, Obs, Acts, _).

belief_step(B, Obs, Acts, Step) :-
    state(B, belief(F, N, LWs0, LL0, Z0, Th, Scheme, R0, Fr0)),
    filter_step(F, Obs, Acts, StepLWs),
    Fr is Fr0 + 1,
    weights_update(LWs0, StepLWs, LWs1, Inc, ESS, Infinite),
    (   Infinite == true
    ->  print_message(warning, ddc_belief(infinite_likelihood(Fr)))
    ;   true
    ),
    B = belief(Key),
    (   Inc =:= -inf
    ->  filter_undo(F),
        Z is Z0 + 1,
        weights_uniform(N, LWs),
        filter_time(F, T),
        print_message(warning, ddc_belief(zero_weight(Fr, N, Z))),
        nb_setval(Key, belief(F, N, LWs, LL0, Z, Th, Scheme, R0, Fr)),
        Step = step{time: T, frame: Fr, ess: 0.0, resampled: false,
                    log_likelihood: Inc, zero_weight: true}
    ;   LL is LL0 + Inc,
        (   resample_needed(ESS, Th, N)
        ->  length(Us, N),
            with_random_stream(state(R0), maplist(random_float_, Us), R),
            resample_log_weights(Scheme, LWs1, Us, _, Is),
            filter_resample(F, Is),
            weights_uniform(N, LWs),
            Resampled = true
        ;   LWs = LWs1, R = R0, Resampled = false
        ),
        filter_time(F, T),
        nb_setval(Key, belief(F, N, LWs, LL, Z0, Th, Scheme, R, Fr)),
        Step = step{time: T, frame: Fr, ess: ESS, resampled: Resampled,
                    log_likelihood: Inc, zero_weight: false}
    ).

random_float_(U) :-
    U is random_float.

		 /*******************************
		 *            QUERIES           *
		 *******************************/

%!  belief_weights(+Belief, -Weights) is det.
%
%   The normalised weights of the particles (they sum to 1).
belief_weights(B, Ws) :-
    state(B, belief(_, _, LWs, _, _, _, _, _, _)),
    weights_normalised(LWs, Ws).

%!  belief_ess(+Belief, -ESS) is det.
%
%   The effective sample size of the current weights (N after resampling).
belief_ess(B, ESS) :-
    state(B, belief(_, _, LWs, _, _, _, _, _, _)),
    weights_ess(LWs, ESS).

%!  belief_time(+Belief, -T) is det.
belief_time(B, T) :-
    state(B, belief(F, _, _, _, _, _, _, _, _)),
    filter_time(F, T).

%!  belief_log_likelihood(+Belief, -LL) is det.
%
%   The sum over the steps of the log of the weighted mean likelihood of
%   their observations (zero-weight steps left out).
belief_log_likelihood(B, LL) :-
    state(B, belief(_, _, _, LL, _, _, _, _, _)).

%!  belief_zero_weight_events(+Belief, -Count) is det.
belief_zero_weight_events(B, Z) :-
    state(B, belief(_, _, _, _, Z, _, _, _, _)).

%!  belief_filter(+Belief, -Filter) is det.
%
%   The underlying filter, for filter_holds/3, filter_values/4, ...
belief_filter(B, F) :-
    state(B, belief(F, _, _, _, _, _, _, _, _)).

%!  belief_probability(+Belief, +Goal, -P) is det.
%
%   The weighted fraction of particles in which Goal holds at the current
%   time (`t` in Goal is the current time; filter_holds/3).
belief_probability(B, Goal, P) :-
    belief_filter(B, F),
    filter_holds(F, Goal, Flags),
    belief_weights(B, Ws),
    foldl(add_flagged, Flags, Ws, 0.0, P).

add_flagged(Flag, W, P0, P) :-
    (   Flag =:= 1 -> P is P0 + W ; P = P0 ).

%!  belief_distribution(+Belief, +Term, -Dist) is det.
%!  belief_distribution(+Belief, +Template, +Goal, -Dist) is det.
%
%   Dist = [P:Value, ...], most probable first (ties in the standard order
%   of the values): the weighted distribution of random variable Term
%   (e.g. maze(0,1):t), or of Template at the first solution of Goal.
%   Particles where it has no value count for no value, so the P then sum
%   to less than 1.
belief_distribution(B, Term, Dist) :-
    belief_distribution(B, V, Term ~= V, Dist).

belief_distribution(B, Template, Goal, Dist) :-
    defined_samples(B, Template, Goal, Samples),
    transpose_pairs(Samples, ByValue),          % Value-Weight, sorted by value
    group_pairs_by_key(ByValue, Groups),
    findall(NegP-(P:V), ( member(V-Ws, Groups), sum_list(Ws, P), NegP is -P ), Keyed),
    keysort(Keyed, Sorted),
    pairs_values(Sorted, Dist).

%!  belief_samples(+Belief, +Term, -Samples) is det.
%
%   Samples = [Weight-Value, ...]: random variable Term's value and weight
%   in each particle where it has one, in particle order.
belief_samples(B, Term, Samples) :-
    defined_samples(B, V, Term ~= V, Samples).

defined_samples(B, Template, Goal, Samples) :-
    belief_filter(B, F),
    filter_values(F, some(Template), Goal, Values),
    belief_weights(B, Ws),
    foldl(defined_sample, Values, Ws, Samples, []).

defined_sample(Value, W, S0, S) :-
    (   Value = some(V) -> S0 = [W-V|S] ; S0 = S ).

%!  belief_mean(+Belief, +Term, -Mean, -Cov) is det.
%
%   The weighted mean and covariance of a numeric or tuple random variable
%   Term over the particles where it has a value: floats for a number; a
%   tuple (M1, ..., Mk) and a list of k rows for a k-tuple.  Raises an
%   error if the values are not numeric or Term has no value anywhere.
belief_mean(B, Term, Mean, Cov) :-
    belief_filter(B, F),
    filter_rows(F, V, Term ~= V, Width, Floats, _),
    (   Width =:= 0
    ->  throw(error(ddc_belief(not_numeric(Term)), _))
    ;   true
    ),
    belief_weights(B, Ws),
    rows(Floats, Width, Rows),
    foldl(defined_row, Rows, Ws, Kept, []),
    pairs_keys_values(Kept, KWs, KRows),
    sum_list(KWs, Total),
    (   Kept \== [], Total > 0
    ->  true
    ;   throw(error(ddc_belief(undefined_everywhere(Term)), _))
    ),
    maplist(divide(Total), KWs, Ns),
    weighted_mean(Ns, KRows, Width, M),
    weighted_cov(Ns, KRows, M, C),
    (   Width =:= 1
    ->  M = [Mean], C = [[Cov]]
    ;   list_tuple(M, Mean), Cov = C
    ).

divide(D, X, Y) :-
    Y is X / D.

rows([], _, []) :- !.
rows(Fs, W, [R|Rs]) :-
    length(R, W),
    append(R, Fs1, Fs),
    rows(Fs1, W, Rs).

defined_row(Row, W, K0, K) :-
    (   maplist(not_nan, Row) -> K0 = [W-Row|K] ; K0 = K ).

not_nan(X) :-
    X =:= X.

weighted_mean(Ws, Rows, Width, M) :-
    length(Zero, Width),
    maplist(=(0.0), Zero),
    foldl(add_weighted_row, Ws, Rows, Zero, M).

add_weighted_row(W, Row, S0, S) :-
    maplist(add_weighted(W), Row, S0, S).

add_weighted(W, X, S0, S) :-
    S is S0 + W*X.

weighted_cov(Ws, Rows, M, C) :-
    findall(CRow,
            ( nth0(I, M, MI),
              findall(CIJ,
                      ( nth0(J, M, MJ),
                        foldl(cov_term(I, J, MI, MJ), Ws, Rows, 0.0, CIJ) ),
                      CRow) ),
            C).

cov_term(I, J, MI, MJ, W, Row, S0, S) :-
    nth0(I, Row, XI),
    nth0(J, Row, XJ),
    S is S0 + W*(XI - MI)*(XJ - MJ).

list_tuple([X], X) :- !.
list_tuple([X|Xs], (X, T)) :-
    list_tuple(Xs, T).

		 /*******************************
		 *          FRAME FILES         *
		 *******************************/

%!  belief_run(+Belief, +File) is det.
%!  belief_run(+Belief, +File, :OnStep) is det.
%
%   Steps the belief once per frame of File (read_frame_file/2's format),
%   reading and stepping line by line; call(OnStep, Step) after each step
%   (belief_step/4's dict).  A bad line or a step the filter refuses raises
%   error(ddc_belief(frame(File, Line, Cause)), _); the steps before it stay
%   done, the belief is as after them.
belief_run(B, File) :-
    belief_run(B, File, ignore_step).

ignore_step(_).

belief_run(B, File, OnStep) :-
    must_be(text, File),
    setup_call_cleanup(open(File, read, In, [encoding(utf8)]),
                       run_frames(In, File, 1, B, OnStep),
                       close(In)).

run_frames(In, File, Line0, B, OnStep) :-
    read_frame(In, File, Line0, Frame, Line),
    (   Frame = frame(At, Obs, Acts)
    ->  catch(belief_step(B, Obs, Acts, Step), E,
              frame_error(File, At, E)),
        call(OnStep, Step),
        run_frames(In, File, Line, B, OnStep)
    ;   true
    ).

%!  read_frame_file(+File, -Frames:list) is det.
%
%   The frames of File, a JSON Lines file in the format of `ddc filter`
%   (docs/filter.md, the JSONL frame format): one JSON object per line with
%   optional "observations" and "actions" lists and a "comment" (ignored);
%   blank lines skipped.  A list item is term text (read in the operator
%   context of module ddc, ground), or, for an observation,
%   {"observation": TERM, "value": V} for `observation(TERM) ~= V`, V a JSON
%   number, string (an atom), true/false or non-empty array (a tuple).
%   Frames = [frame(Line, Observations, Actions), ...], Line the 1-based
%   line number.  The Python side (bridge.frames, used by `ddc filter`)
%   reads frame files with this predicate.
%
%   @error ddc_belief(frame(File, Line, Cause)) for the first bad line;
%   its message is "File:Line: cause" (for an item, "observations[I]: ..."
%   or "actions[I]: ...").
read_frame_file(File, Frames) :-
    must_be(text, File),
    setup_call_cleanup(open(File, read, In, [encoding(utf8)]),
                       read_frames(In, File, 1, Frames),
                       close(In)).

read_frames(In, File, Line0, Frames) :-
    read_frame(In, File, Line0, Frame, Line),
    (   Frame == end_of_file
    ->  Frames = []
    ;   Frames = [Frame|Rest],
        read_frames(In, File, Line, Rest)
    ).

%   read_frame(+In, +File, +Line0, -Frame, -Line): the next frame of In
%   (frame(At, Observations, Actions), or end_of_file), blank lines skipped;
%   Line0 is the number of the next line of In, Line that of the line after
%   the frame.
read_frame(In, File, Line0, Frame, Line) :-
    read_line_to_string(In, Text),
    (   Text == end_of_file
    ->  Frame = end_of_file,
        Line = Line0
    ;   Line1 is Line0 + 1,
        (   normalize_space(string(""), Text)
        ->  read_frame(In, File, Line1, Frame, Line)
        ;   catch(frame_terms(Text, Obs, Acts), E,
                  frame_error(File, Line0, E)),
            Frame = frame(Line0, Obs, Acts),
            Line = Line1
        )
    ).

frame_error(File, Line, E) :-
    (   E = error(_, _)
    ->  throw(error(ddc_belief(frame(File, Line, E)), _))
    ;   throw(E)
    ).

frame_terms(Text, Obs, Acts) :-
    catch(atom_json_dict(Text, D, [value_string_as(string)]), _,
          throw(error(frame_syntax(invalid_json), _))),
    (   is_dict(D) -> true ; throw(error(frame_syntax(not_an_object), _)) ),
    dict_keys(D, Keys),
    (   member(K, Keys), \+ memberchk(K, [observations, actions, comment])
    ->  throw(error(frame_syntax(unknown_key(K)), _))
    ;   true
    ),
    get_dict_default(observations, D, ObsItems),
    get_dict_default(actions, D, ActItems),
    foldl(frame_item(observations, observation_term), ObsItems, Obs, 1, _),
    foldl(frame_item(actions, text_term), ActItems, Acts, 1, _).

%   frame_item(+Key, :Read, +Item, -Term, +I0, -I): Item, the I0-th of
%   list Key, read by Read; its errors name Key and I0.
frame_item(Key, Read, Item, Term, I0, I) :-
    I is I0 + 1,
    catch(call(Read, Item, Term), error(frame_syntax(Cause), _),
          throw(error(frame_syntax(item(Key, I0, Cause)), _))).

dict_keys(D, Keys) :-
    dict_pairs(D, _, Pairs),
    pairs_keys(Pairs, Keys).

get_dict_default(K, D, L) :-
    (   get_dict(K, D, L0)
    ->  (   is_list(L0) -> L = L0 ; throw(error(frame_syntax(not_a_list(K)), _)) )
    ;   L = []
    ).

observation_term(Item, T) :-
    (   string(Item)
    ->  text_term(Item, T)
    ;   is_dict(Item), dict_keys(Item, Ks), msort(Ks, [observation, value]),
        string(Item.observation)
    ->  text_term(Item.observation, X),
        json_value(Item.value, V),
        T = (observation(X) ~= V)
    ;   throw(error(frame_syntax(bad_observation(Item)), _))
    ).

text_term(Text, T) :-
    (   string(Text) -> true ; throw(error(frame_syntax(not_term_text(Text)), _)) ),
    (   normalize_space(string(""), Text)
    ->  throw(error(frame_syntax(empty_text), _))
    ;   true
    ),
    catch(check_text_nesting(Text, nowhere), _, throw(error(frame_syntax(too_deep), _))),
    catch(term_string(T, Text, [module(ddc)]), E,
          throw(error(frame_syntax(term(Text, E)), _))),
    (   ground(T) -> true ; throw(error(frame_syntax(not_ground(Text)), _)) ).

json_value(V, V) :- number(V), !.
json_value(S, A) :- string(S), !, atom_string(A, S).
json_value(B, B) :- ( B == true ; B == false ), !.
json_value([X|Xs], T) :- !,
    maplist(json_value, [X|Xs], Vs),
    list_tuple(Vs, T).
json_value(V, _) :-
    throw(error(frame_syntax(bad_value(V)), _)).

		 /*******************************
		 *           MESSAGES           *
		 *******************************/

:- multifile prolog:message//1.

prolog:message(ddc_belief(zero_weight(Frame, N, Z))) -->
    [ 'step ~w: every particle got weight 0; kept the ~w pre-step particles with uniform weights (event ~w)'-[Frame, N, Z] ].
prolog:message(ddc_belief(infinite_likelihood(Frame))) -->
    [ 'step ~w: infinite likelihoods; keeping only those particles'-[Frame] ].
prolog:message(error(ddc_belief(frame(File, Line, Cause)), _)) -->
    [ '~w:~w: '-[File, Line] ],
    frame_cause(Cause).
prolog:message(error(ddc_belief(not_numeric(Term)), _)) -->
    [ 'mean of ~q: the values are not numeric'-[Term] ].
prolog:message(error(ddc_belief(undefined_everywhere(Term)), _)) -->
    [ 'mean of ~q: undefined in every particle'-[Term] ].

frame_cause(error(frame_syntax(C), _)) --> !,
    frame_syntax(C).
frame_cause(E) -->
    '$messages':translate_message(E).

frame_syntax(item(Key, I, Cause)) --> !,
    [ '~w[~w]: '-[Key, I] ],
    frame_syntax(Cause).
frame_syntax(invalid_json) --> !, [ 'invalid JSON' ].
frame_syntax(not_an_object) --> !, [ 'a line must be a JSON object' ].
frame_syntax(unknown_key(K)) --> !,
    [ 'unknown key ~q; use observations, actions, comment'-[K] ].
frame_syntax(not_a_list(K)) --> !, [ '~w must be a list'-[K] ].
frame_syntax(bad_observation(I)) --> !,
    [ 'an observation is term text or {"observation": TERM, "value": V}, not ~q'-[I] ].
frame_syntax(not_term_text(X)) --> !, [ 'not term text: ~q'-[X] ].
frame_syntax(too_deep) --> !,
    { max_nesting(Max) },
    [ 'a term whose brackets nest deeper than ~D, the most the reader takes'-[Max] ].
frame_syntax(term(Text, E)) --> !,
    [ 'syntax error in ~q'-[Text] ],
    syntax_detail(E).
frame_syntax(not_ground(Text)) --> !, [ 'not ground: ~q'-[Text] ].
frame_syntax(empty_text) --> !, [ 'empty term text' ].
frame_syntax(bad_value(V)) --> [ 'cannot use ~q as an observed value'-[V] ].

%   syntax_detail(+Error): ": " and what the reader said, e.g. "Operator
%   expected" (nothing if it has no message).
syntax_detail(error(syntax_error(What), _)) -->
    { catch('$messages':translate_message(error(syntax_error(What), _), Lines, []), _, fail),
      Lines = ['Syntax error: '|Detail], Detail \== []
    }, !,
    [ ': ' ], Detail.
syntax_detail(_) --> [].

/** <module> Static queries of the DDC system

Part of the DDC system (ddc.pl is the module users load).  Answers
probability, expectation and distribution queries on a loaded
program by likelihood weighting over sampled worlds, and samples a
single world (ddc_sample_world/4).
*/

:- module(ddc_query,
          [ query/2,                    % :Query, -P
            query/3,                    % :Query, -P, +Options
            query/4,                    % +Evidence, :Query, -P, +Options
            query/5,                    % +PosEv, +NegEv, +Query, +N, -P
            query/8,                    % +PosEv, +NegEv, +Query, ?X, +N, -Avg, -SuccSum, -Sum
            expectation/5,              % +Evidence, +Query, ?X, -E, +Options
            distribution/5,             % +Evidence, +Query, ?X, -Dist, +Options
            ddc_query/6,                % +Module, +Evidence, +Query, +Options, -P, -Stats
            ddc_query_text/6,           % +Module, +QueryText, +EvidenceText, +N, +Seed, -Result
            ddc_expectation_text/7,     % +Module, +ValueText, +QueryText, +EvidenceText, +N, +Seed, -Result
            ddc_distribution_text/7,    % +Module, +ValueText, +QueryText, +EvidenceText, +N, +Seed, -Pairs
            ddc_sample_world/4,         % +Module, +Query, +Options, -Facts
            ddc_sample_text/5,          % +Module, +TemplateText, +GoalText, +Seed, -Texts
            no_program_loaded/1         % +PI
          ]).

:- use_module(library(lists)).
:- use_module(library(apply)).
:- use_module(library(aggregate)).
:- use_module(library(option)).
:- use_module(library(error)).
:- use_module(library(pairs)).
:- use_module('../lang/ddc_records').
:- use_module(ddc_store).
:- use_module('../lang/ddc_nesting').
:- use_module('../lang/ddc_body').
:- use_module(ddc_world).
:- use_module('../lang/ddc_programs').

:- use_module('../lang/ddc_ops').

%   Arithmetic compiled to virtual-machine instructions (local to this
%   file; see ddc.pl).
:- set_prolog_flag(optimise, true).

%   The weighted sums over the samples that count (those of the smallest
%   evidence dimension), as ddc_run/7 gives them: the sums of w, w^2, w*y,
%   w^2*y, w^2*y^2 and w*q (y = q: the query's weight, prob, or q*x, the
%   value's, value), the value-weight pairs (dist), the number of samples
%   that count, and the sums of w^2*q*y and w^2*q^2.
:- record_type estimate(w_sum, w2_sum, wy_sum, w2y_sum, w2y2_sum, wq_sum, pairs, counted,
                        w2qy_sum, w2q2_sum).

%!  default_samples(-N) is det.
%
%   The number of sampled worlds of a query without option samples(N).
default_samples(10000).

%!  query(+Query, -P) is det.
%!  query(+Query, -P, +Options) is det.
%
%   P is the probability of Query (a goal, possibly a conjunction, possibly
%   time-indexed: `pos(1):3 > 0`) in the program loaded last, estimated
%   from 10,000 samples (option samples(N)).  See query/4.
query(Q, P) :-
    query(true, Q, P, []).
query(Q, P, Options) :-
    query(true, Q, P, Options).

%!  query(+Evidence, +Query, -P, +Options) is det.
%
%   P = P(Query | Evidence), by likelihood weighting.  Evidence is a goal,
%   a list of goals or `true`.  Options:
%     - samples(N): number of sampled worlds (default 10000,
%       default_samples/1)
%     - seed(S): set_random(seed(S)) first (same seed, same answer)
%     - stderr(-SE): the standard error of the estimate (delta method for
%       the self-normalised estimator)
%     - ess(-ESS): the effective sample size (sum w)^2 / sum w^2 of the
%       samples that count; ESS < N shows how much the evidence cost
%     - program(M): the program (default: the one loaded last)
%     - time(T): the time `t` means in the query (default 0); e.g.
%       query(left(1,2):t ~= true, P, [time(3)]) unrolls to time 3.
%   Throws error(ddc(zero_evidence(E), query), _) if the evidence has
%   weight 0 in every sample.
query(Ev, Q, P, Options) :-
    query_program(Options, M),
    ddc_query(M, Ev, Q, Options, P, Stats),
    Stats = stats(SE, ESS, _, _),
    option(stderr(SE), Options, _),
    option(ess(ESS), Options, _).

%!  query(+PosEv, +NegEv, +Query, +N, -P) is det.
%
%   The original system's form: PosEv a list of goals that hold, NegEv a
%   list of goals that do not (proven, unlike the original which only
%   looked them up among recorded facts), N samples.
query(PosEv, NegEv, Q, N, P) :-
    neg_evidence(PosEv, NegEv, Ev),
    query(Ev, Q, P, [samples(N)]).

%!  query(+PosEv, +NegEv, +Query, ?X, +N, -Avg, -SuccSum, -Sum) is det.
%
%   The original's expectation form: Avg = E[X * 1(Query) | evidence]
%   (SuccSum = sum of w*X over samples where Query holds, Sum = sum of
%   evidence weights).  With a Query that always holds it is E[X | e].
query(PosEv, NegEv, Q, X, N, Avg, SuccSum, Sum) :-
    neg_evidence(PosEv, NegEv, Ev),
    query_program([], M),
    ddc_run(M, Ev, Q, X, [samples(N)], value, R),
    estimate_w_sum(R, Sum), estimate_wy_sum(R, SuccSum),
    Avg is SuccSum / Sum.

neg_evidence(PosEv, NegEv, Ev) :-
    must_be(list, PosEv), must_be(list, NegEv),
    findall(\+ G, member(G, NegEv), Negs),
    append(PosEv, Negs, Ev).

%!  expectation(+Evidence, +Query, ?X, -E, +Options) is det.
%
%   E = E[X | Evidence, Query]: the weighted mean of X (numeric, bound by
%   the first proof of Query) over the worlds where Query holds.  For
%   E[X | e] use a Query that binds X and always holds (`g ~= X`).  (The
%   original's query/8 divides by the evidence weight instead; query/8
%   keeps that.)  Options as query/4 (stderr(SE) is the standard error).
expectation(Ev, Q, X, E, Options) :-
    query_program(Options, M),
    ddc_run(M, Ev, Q, X, Options, value, R),
    estimate_wy_sum(R, SWY), estimate_w2y2_sum(R, SW2Y2), estimate_wq_sum(R, SWQ),
    estimate_w2qy_sum(R, SW2QY), estimate_w2q2_sum(R, SW2Q2),
    (   SWQ > 0 -> true ; throw(error(ddc(query_never_holds(Q), query), _)) ),
    E is SWY / SWQ,
    (   option(stderr(SE), Options)
    ->  SE is sqrt(max(0.0, SW2Y2 - 2*E*SW2QY + E*E*SW2Q2)) / SWQ
    ;   true
    ).

%!  distribution(+Evidence, +Query, ?X, -Dist, +Options) is det.
%
%   Dist = [P:Value, ...], the posterior distribution of X (bound by the
%   first proof of Query in each world), sorted by value; worlds where
%   Query fails are left out (Dist is conditioned on Query holding).
distribution(Ev, Q, X, Dist, Options) :-
    query_program(Options, M),
    ddc_run(M, Ev, Q, X, Options, dist, R),
    estimate_wq_sum(R, SWQ), estimate_pairs(R, Pairs),
    (   SWQ > 0 -> true ; throw(error(ddc(query_never_holds(Q), query), _)) ),
    findall(P:V, ( member(V-Wv, Pairs), P is Wv / SWQ ), Dist).

query_program(Options, M) :-
    (   option(program(M0), Options)
    ->  M = M0
    ;   current_program_(M0)
    ->  M = M0
    ;   no_program_loaded(query_program/2)
    ).

%!  no_program_loaded(+PI) is det.
%
%   Raises the ISO error of a query (predicate PI) asked when no program
%   is loaded: existence_error(ddc_program, current).
no_program_loaded(PI) :-
    throw(error(existence_error(ddc_program, current),
                context(PI, 'no DC program is loaded (use ddc_load/1)'))).

%!  ddc_query(+Module, +Evidence, +Query, +Options, -P, -Stats) is det.
%
%   Stats = stats(StdErr, ESS, SamplesThatCount, Samples).
ddc_query(M, Ev, Q, Options, P, stats(SE, ESS, NPos, N)) :-
    default_samples(Default),
    option(samples(N), Options, Default),
    ddc_run(M, Ev, Q, _, Options, prob, R),
    estimate_w_sum(R, SW), estimate_w2_sum(R, SW2), estimate_wy_sum(R, SWY),
    estimate_w2y_sum(R, SW2Y), estimate_w2y2_sum(R, SW2Y2), estimate_counted(R, NPos),
    P is SWY / SW,
    SE is sqrt(max(0.0, SW2Y2 - 2*P*SW2Y + P*P*SW2)) / SW,
    ESS is SW*SW / SW2.

%!  ddc_query_text(+Module, +QueryText, +EvidenceText, +Samples, +Seed, -Result) is det.
%
%   For the Python bridge: the texts are parsed with the DC operators
%   (EvidenceText '' means no evidence; Seed `none` means do not reseed).
%   Result = [P, StdErr, ESS, Samples].  Errors are thrown as by query/4.
ddc_query_text(M, QT, ET, N, Seed, [P, SE, ESS, N]) :-
    text_goal(QT, Q),
    (   empty_text(ET) -> Ev = true ; text_goal(ET, Ev) ),
    (   Seed == none -> Opts = [samples(N)] ; Opts = [samples(N), seed(Seed)] ),
    ddc_query(M, Ev, Q, Opts, P, stats(SE, ESS, _, N)).

%!  ddc_expectation_text(+Module, +ValueText, +QueryText, +EvidenceText, +N, +Seed, -Result) is det.
%
%   Result = [E, StdErr, ESS, N] for E[Value | Evidence, Query]; the
%   texts share variables (Value is read together with Query).
ddc_expectation_text(M, XT, QT, ET, N, Seed, [E, SE, ESS, N]) :-
    format(string(Both), "(~w)-(~w)", [XT, QT]),
    text_goal(Both, X-Q),
    (   empty_text(ET) -> Ev = true ; text_goal(ET, Ev) ),
    (   Seed == none -> Opts = [samples(N)] ; Opts = [samples(N), seed(Seed)] ),
    expectation(Ev, Q, X, E, [stderr(SE), program(M)|Opts]),
    ESS = N.

%!  ddc_distribution_text(+Module, +ValueText, +QueryText, +EvidenceText, +N, +Seed, -Pairs) is det.
%
%   Pairs = [[P, ValueText], ...], the distribution of Value given
%   Evidence and Query, values written with writeq.
ddc_distribution_text(M, XT, QT, ET, N, Seed, Pairs) :-
    format(string(Both), "(~w)-(~w)", [XT, QT]),
    text_goal(Both, X-Q),
    (   empty_text(ET) -> Ev = true ; text_goal(ET, Ev) ),
    (   Seed == none -> Opts = [samples(N)] ; Opts = [samples(N), seed(Seed)] ),
    distribution(Ev, Q, X, D, [program(M)|Opts]),
    findall([P, VT], ( member(P:V, D), format(string(VT), "~q", [V]) ), Pairs).

%!  ddc_sample_text(+Module, +TemplateText, +GoalText, +Seed, -Texts:list(string)) is det.
%
%   The solutions of findall(Template, Goal, L) in one world of Module's
%   program sampled with Seed (ddc_sample_world/4), each written back as
%   text (term_string/2); the two texts are read together, so they share
%   variables.
ddc_sample_text(M, TT, GT, Seed, Texts) :-
    must_be(integer, Seed),
    format(string(Both), "(~w)-(~w)", [TT, GT]),
    text_goal(Both, T-G),
    ddc_sample_world(M, findall(T, G, L), [seed(Seed)], _),
    findall(X, ( member(Y, L), term_string(Y, X) ), Texts).

empty_text(T) :- var(T), !.
empty_text('').
empty_text("").
empty_text(none).
empty_text('None').

text_goal(Text, G) :-
    check_text_nesting(Text, query),
    catch(term_string(G, Text, [module(ddc)]), error(syntax_error(E), _),
          ( format(atom(A), "~w", [Text]),
            throw(error(ddc(syntax_error(E), text(A)), _)) )).

%   ddc_run(+M, +Ev, +Q, ?X, +Options, +Mode, -Estimate): the estimate
%   record over the samples of the smallest evidence dimension.
ddc_run(M, Ev0, Q, X, Options, Mode, R) :-
    (   program_file_(M, _) -> true
    ;   throw(error(existence_error(ddc_program, M),
                    context(_, 'no DC program of that name is loaded')))
    ),
    default_samples(Default),
    option(samples(N), Options, Default),
    must_be(positive_integer, N),
    option(time(Time), Options, 0),
    (   option(seed(Seed), Options) -> set_random(seed(Seed)) ; true ),
    evidence_goal(Ev0, EvG),
    M:'$ddc_info'(Info),
    prepare_query(M, Info, Time, EvG, Q, X, Ev, Id),
    call_cleanup(
        findall(S, ( between(1, N, I), one_sample(M, Id, Time, Ev, I, S) ), Samples),
        retractall(M:'$ddc_tmp'(Id, _, _, _))),
    (   Samples == []
    ->  throw(error(ddc(zero_evidence(Ev0), query), _))
    ;   true
    ),
    min_dx(Samples, 1000000000, MinDX),
    summarise(Mode, Samples, MinDX, R).

%   one_sample(+M, +Id, +Time, +Ev, -s(W, DX, QW, X)): fails when the
%   evidence fails or has weight 0; QW is 0.0 when the query fails.
one_sample(M, Id, Time, Ev, I, s(W, DX, QW, X)) :-
    overlap_checked_worlds(Checked),
    (   I =< Checked -> Check = true ; Check = false ),
    new_world(M, Time, -1, Ev, Check, Wd),
    static_world(Wd),
    M:'$ddc_tmp'(Id, s, Wd, Out),       % evidence, then the query (prepare_query/8)
    world_log_weight(Wd, LW),
    (   LW == 0.0 -> W = 1.0
    ;   LW > -inf, W is exp(LW), W > 0.0
    ),
    world_density_dims(Wd, DX),
    (   Out = q(X0)
    ->  world_query_log_weight(Wd, QLW),
        (   QLW == 0.0 -> QW = 1.0 ; exp_w(QLW, QW) ),
        X = X0
    ;   QW = 0.0, X = '$none'
    ).

%   '$ev_holds'(+W): the evidence proven so far has a weight above 0 (the
%   query is not proven in a world of weight 0).
'$ev_holds'(W) :-
    world_log_weight(W, LW),
    LW > -inf.

min_dx([], M, M).
min_dx([s(_, DX, _, _)|Ss], M0, M) :-
    (   DX < M0 -> min_dx(Ss, DX, M) ; min_dx(Ss, M0, M) ).

%   summarise(+Mode, +Samples, +MinDX, -Estimate): the estimate record
%   over the samples of dimension MinDX; y = QW (prob), QW*X (value).
summarise(dist, Samples, MinDX, estimate(SW, 0.0, 0.0, 0.0, 0.0, SWQ, Pairs, NPos, 0.0, 0.0)) :- !,
    findall(X-WQ, ( member(s(W, MinDX, QW, X), Samples), QW > 0.0, WQ is W*QW ), XWs),
    msort(XWs, Sorted),
    group_pairs_by_key(Sorted, Groups),
    findall(X-S, ( member(X-Ws, Groups), sum_list(Ws, S) ), Pairs),
    aggregate_all(count, member(s(_, MinDX, _, _), Samples), NPos),
    aggregate_all(sum(W), member(s(W, MinDX, _, _), Samples), SW),
    aggregate_all(sum(V), member(_-V, Pairs), SWQ).
summarise(prob, Samples, MinDX, estimate(SW, SW2, SWY, SW2Y, SW2Y2, SWY, [], N, SW2Y, SW2Y2)) :- !,
    psums(Samples, MinDX, 0.0, 0.0, 0.0, 0.0, 0.0, 0, SW, SW2, SWY, SW2Y, SW2Y2, N).
summarise(Mode, Samples, MinDX, R) :-
    sums(Samples, Mode, MinDX, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0, 0.0, 0.0, R).

%   Probability: Y = QW.
psums([], _, SW, SW2, SWY, SW2Y, SW2Y2, N, SW, SW2, SWY, SW2Y, SW2Y2, N).
psums([s(W, DX, Y, _)|Ss], MinDX, A0, B0, C0, D0, E0, N0, A, B, C, D, E, N) :-
    (   DX =:= MinDX
    ->  W2 is W*W,
        A1 is A0 + W, B1 is B0 + W2,
        (   Y =:= 0.0
        ->  C1 = C0, D1 = D0, E1 = E0
        ;   C1 is C0 + W*Y, W2Y is W2*Y, D1 is D0 + W2Y, E1 is E0 + W2Y*Y
        ),
        N1 is N0 + 1,
        psums(Ss, MinDX, A1, B1, C1, D1, E1, N1, A, B, C, D, E, N)
    ;   psums(Ss, MinDX, A0, B0, C0, D0, E0, N0, A, B, C, D, E, N)
    ).

sums([], _, _, SW, SW2, SWY, SW2Y, SW2Y2, SWQ, N, SW2QY, SW2Q2,
     estimate(SW, SW2, SWY, SW2Y, SW2Y2, SWQ, [], N, SW2QY, SW2Q2)).
sums([s(W, DX, Q, X)|Ss], Mode, MinDX, SW0, SW20, SWY0, SW2Y0, SW2Y20, SWQ0, N0, A0, B0, R) :-
    (   DX =:= MinDX
    ->  sample_y(Mode, Q, X, Y),
        W2 is W*W,
        SW is SW0 + W, SW2 is SW20 + W2,
        SWY is SWY0 + W*Y, SW2Y is SW2Y0 + W2*Y, SW2Y2 is SW2Y20 + W2*Y*Y,
        SWQ is SWQ0 + W*Q, A is A0 + W2*Q*Y, B is B0 + W2*Q*Q,
        N is N0 + 1,
        sums(Ss, Mode, MinDX, SW, SW2, SWY, SW2Y, SW2Y2, SWQ, N, A, B, R)
    ;   sums(Ss, Mode, MinDX, SW0, SW20, SWY0, SW2Y0, SW2Y20, SWQ0, N0, A0, B0, R)
    ).

sample_y(prob, Q, _, Q).
sample_y(value, Q, X, Y) :-
    (   Q =:= 0.0 -> Y = 0.0
    ;   number(X) -> Y is Q*X
    ;   throw(error(type_error(number, X),
                    context(ddc:expectation/5, 'the expectation needs a number')))
    ).

evidence_goal(V, _) :- var(V), !, instantiation_error(V).
evidence_goal([], true) :- !.
evidence_goal(L, G) :- is_list(L), !, conj_from_list(L, G).
evidence_goal(G, G).

%   Compile evidence and query into two temporary clauses of M; `t` is
%   the query time.
prepare_query(M, Info, Time, EvG, Q, X, Ev, Id) :-
    flag(ddc_query_id, Id, Id+1),
    copy_term(EvG, EvG1),
    Ctx = ctx(W, Time, Info, query),
    conj_list(EvG1, EvLs),
    evidence_map(EvLs, Ctx, Ev),
    compile_body(EvG1, Ctx, EvCode),
    Ctx2 = ctx(W, Time, Info, query),
    copy_term(Q-X, Q2-X2),
    conj_list(Q2, QLs),
    maplist(query_literal(Ctx2), QLs, QCodes),
    conj_from_list(QCodes, QCode),
    %   one call per sample: the first proof of the evidence, then the query
    %   (Out = q(X) when it holds, none when it fails)
    optimised(assertz(M:('$ddc_tmp'(Id, s, W, Out) :-
                            EvCode, !,
                            (   ddc_query:'$ev_holds'(W), QCode
                            ->  Out = q(X2)
                            ;   Out = none
                            )))).

%   Ground top-level evidence literals h ~= v are weighted, not sampled.
evidence_map(Ls, Ctx, Ev) :-
    findall((X-T)-V,
            ( member(L, Ls), nonvar(L), L = (H ~= V), ground(H), ground(V),
              read_key_code(H, Ctx, X, T, TG), call(TG), ground(X-T) ),
            Ev).

query_literal(Ctx, G, Code) :-
    nonvar(G), G = (H ~= V), \+ var(V), !,     % a value that may be ground: weighted
    read_key_code(H, Ctx, X, T, TG),
    ctx_world(Ctx, W),
    Code = (TG, ddc_world:'$read_q'(X, T, V, W)).
query_literal(Ctx, G, Code) :-
    compile_body(G, Ctx, Code).

exp_w(L, W) :-
    (   L == 0.0 -> W = 1.0
    ;   L =:= -inf -> W = 0.0
    ;   W is exp(L)
    ).

%!  ddc_sample_world(+Module, +Query, +Options, -Facts) is semidet.
%
%   Proves Query in one sampled world (option time(T), seed(S)) and
%   returns what the world holds as Key-Value pairs (the original's
%   generate_backward).  Options values(Vs) (X-Time-Value triples) and
%   facts(Fs) (atoms, as a filter step's actions) are put into the world
%   first; with facts, a predicate the program does not define is looked
%   up among them, as in a filter step.
ddc_sample_world(M, Q, Options, Facts) :-
    option(time(Time), Options, 0),
    option(values(Vs), Options, []),
    option(facts(Fs), Options, []),
    must_be(list, Vs), must_be(list, Fs),
    (   option(seed(Seed), Options) -> set_random(seed(Seed)) ; true ),
    M:'$ddc_info'(Info),
    new_world(M, Time, -1, [], W),
    (   Fs == [] -> static_world(W) ; group_facts(Fs, Gs), nb_set_world_facts(W, Gs) ),
    world_store(W, S0),
    forall(member(X-T-V, Vs), store_put(S0, X-T, V)),
    Ctx = ctx(W, Time, Info, query),
    compile_body(Q, Ctx, Code),
    once(M:Code),
    world_store(W, S),
    store_entries(S, Facts).

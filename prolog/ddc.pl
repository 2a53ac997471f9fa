/*  ddc.pl -- Dynamic Distributional Clauses for SWI-Prolog.

    The DDC system of the project: the DC language of section 2.2 of the paper
    (distributional clauses, derived atoms, time-indexed terms), compiled
    into Prolog, with likelihood-weighted backward sampling for static
    queries and the particle filter over time.  This is the module users
    load (`swipl -p library=prolog`, then `use_module(library(ddc))`; or by
    path); the work is done by modules of one job each, a folder per
    subsystem below prolog/ddc/ (module names keep their ddc_ prefix):

      lang/     the language: ddc_ops.pl (the operators ~, ~=, :=, <-, pr),
                ddc_records.pl (records with named fields), ddc_source.pl
                (the one reader of DC files, the learner's too), ddc_read.pl
                (what a program's terms mean), ddc_compile.pl and ddc_body.pl
                (compiling items and clause bodies), ddc_programs.pl (the
                programs loaded into modules, ddc_load/1,2), ddc_dist.pl
                (distributions), ddc_models.pl (models of learned clauses),
                ddc_errors.pl (errors at run time), ddc_nesting.pl
      runtime/  possible worlds: ddc_world.pl (the runtime compiled clauses
                call), ddc_store.pl (a world's store), ddc_query.pl (static
                queries, query/2..8, expectation/5, ...), ddc_pool.pl (group
                split, seeds and worker threads), ddc_rows.pl (values as rows
                of floats), ddc_rename.pl (constants renamed in values)
      filter/   the filter API (ddc_filter.pl, filter_*) over one engine
                interface; ddc_particles.pl the per-particle engine,
                ddc_filter_batched.pl the batched one (batch/) behind it;
                ddc_belief.pl the weighted belief for swipl users;
                ddc_bridge.pl the Python side's calls
      batch/    the batched engine (ddc_batch*.pl) and its column library
                in C (c/ddc_columns.c)
      learn/    the structure learner (library(ddc/learn), prolog/ddc/learn.pl)
      compat/   the original DC/DCPF's programs and entry points

    Each of these modules sets the flag optimise, which is local to its
    file: arithmetic is compiled to virtual-machine instructions instead
    of calls to is/2 and friends, about a fifth fewer instructions per
    sample.  Program clauses are asserted the same way
    (ddc_programs:optimised/1).
*/

:- module(ddc,
          [ ddc_load/1,                 % +File
            ddc_load/2,                 % +File, ?Module
            ddc_program/1,              % -Module (the program loaded last)
            query/2,                    % :Query, -P
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
            ddc_sample_text/5,          % +Module, +TemplateText, +GoalText, +Seed, -Texts
            ddc_sample_world/4,         % +Module, +Query, +Options, -Facts
            filter_new/4,               % +ProgramFile, +N, +Seed, -Filter
            filter_new/5,               % +ProgramFile, +N, +Seed, +Options, -Filter
            filter_step/4,              % +Filter, +Observations, +Actions, -LogWeights
            filter_undo/1,              % +Filter
            filter_resample/2,          % +Filter, +Indices
            filter_rename/3,            % +Filter, +Renaming, +Particles
            filter_holds/3,             % +Filter, +Goal, -Flags
            filter_values/4,            % +Filter, +Template, +Goal, -Values
            filter_rows/6,              % +Filter, +Template, +Goal, -Width, -Floats, -Values
            filter_indices/5,           % +Filter, ?Template, +Goal, +Atoms, -Indices
            filter_time/2,              % +Filter, -T
            filter_engine/2,            % +Filter, -Engine
            filter_size/2,              % +Filter, -N
            filter_statistics/2,        % +Filter, -Stats
            filter_free/1,              % +Filter
            op(700, xfx, ~),
            op(700, xfx, ~=),
            op(1105, xfx, :=),
            op(1105, xfx, <-),
            op(1150, xfx, pr)
          ]).


:- use_module('ddc/lang/ddc_read', [resolve_file/2, dist_sugar/2]).
:- use_module('ddc/lang/ddc_programs', [load_program/2, set_current_program/1, current_program_/1]).
:- use_module('ddc/runtime/ddc_query').
:- use_module('ddc/filter/ddc_filter', [ filter_new/4, filter_new/5, filter_step/4, filter_undo/1,
                            filter_resample/2, filter_rename/3, filter_holds/3, filter_values/4,
                            filter_rows/6, filter_indices/5, filter_time/2, filter_engine/2, filter_size/2,
                            filter_statistics/2, filter_free/1, filter_call/2 ]).
:- use_module('ddc/runtime/ddc_world', [eval_dist/2]).
%   (filter_call/2, dist_sugar/2 and eval_dist/2 are imported for the
%   callers that reach them as ddc:...: bench/filter_step.py and
%   ddc_learn_facts.pl.)
:- reexport('ddc/lang/ddc_models').       % logistic/3, linear/3, softmax/3, mean_list/2, ...

/** <module> Dynamic Distributional Clauses

## API

  - ddc_load(+File), ddc_load(+File, ?Module), ddc_program(-Module)
    (ddc_programs.pl)
  - query(+Query, -P), query(+Query, -P, +Options),
    query(+Evidence, +Query, -P, +Options), query(+PosEv, +NegEv, +Query, +N, -P),
    query(+PosEv, +NegEv, +Query, ?X, +N, -Avg, -SuccSum, -Sum),
    expectation(+Evidence, +Query, ?X, -E, +Options),
    distribution(+Evidence, +Query, ?X, -Dist, +Options),
    ddc_query(+Module, +Evidence, +Query, +Options, -P, -stats(SE, ESS, NCounted, N)),
    ddc_sample_world(+Module, +Query, +Options, -Facts) (ddc_query.pl)
  - Python bridge helpers: ddc_query_text/6, ddc_expectation_text/7,
    ddc_distribution_text/7, ddc_sample_text/5 (ddc_query.pl)
  - logistic(+Inputs, +Weights, -P), linear(+Inputs, +Weights, -Y),
    softmax(+Inputs, +WeightRows, -Ps), mean_list/2, mode_list/2,
    antimode_list/2, and the rest of ddc_models.pl's exports (re-exported)
  - Particle filter (ddc_filter.pl): filter_new(+ProgramFile, +N, +Seed, -Filter),
    filter_new(+ProgramFile, +N, +Seed, +Options, -Filter),
    filter_step(+Filter, +Observations, +Actions, -LogWeights), filter_undo(+Filter),
    filter_resample(+Filter, +Indices),
    filter_rename(+Filter, +Renaming, +Particles) (constants renamed in chosen particles),
    filter_holds(+Filter, +Goal, -Flags),
    filter_values(+Filter, +Template, +Goal, -Values),
    filter_rows(+Filter, +Template, +Goal, -Width, -Floats, -Values),
    filter_indices(+Filter, ?Template, +Goal, +Atoms, -Indices),
    filter_time(+Filter, -T), filter_engine(+Filter, -Engine),
    filter_size(+Filter, -N), filter_statistics(+Filter, -Stats), filter_free(+Filter);
    filter_new/5 with share(false) computes
    every value in every particle (see "Shared values" in ddc_world.pl), threads(K) steps the
    particles in K threads, engine(auto|batched|per_particle) picks the engine: the
    batched one (ddc_batch.pl, each clause evaluated once for a batch of particles) for
    a program in its fragment, by default

## Loading

    ?- ddc_load('prolog/examples/tutorial.pl'), query(coin ~= true, P).

ddc_load/1 reads a program file and compiles it into a module of its own
(named after the absolute file name; ddc_load/2 names it).  Several
programs live side by side; loading a file again replaces its program
atomically: if the new text has an error, the exception names file:line and
the previously loaded program stays as it was.  Loads run one at a time
(ddc_programs:load_program/2); a filter compiles its program into a module of its own
that no later load replaces (filter_new/5).  A Prolog file may also load
a program as a directive: `:- use_module(library(ddc)). :- ddc_load(model).`

## Language

  - `H ~ D := Body.`, `H ~ D.`, `H := Body.` (`H := true.` is a fact); the
    paper's `<-` is a synonym of `:=`; a trailing `pr N` is accepted and
    ignored (priorities only matter to forward samplers).
  - Time: `h:t`, `h:t+1`, `h:0` (also `h:N`) in heads and bodies; the
    original's `current(h)`, `next(h)`, `prior(h)` mean the same.
  - Body literals: `H ~= V`, derived atoms, `\+ G`, `(A;B)`, `(A->B;C)`,
    Prolog builtins and library(lists) predicates, findall/3 (its goal may
    use DC literals), findall_forward/3 (same), true(P) (a fresh flip at
    each call), sample(D, X) (inline draw), belief(A) (A is ground),
    timestep(T), the models and aggregates of learned clauses (logistic/3,
    linear/3, softmax/3, mean_list/2, mode_list/2, antimode_list/2:
    ddc_models.pl), predicates declared with
    `builtin(Pattern).` or defined by plain Prolog clauses in the program
    file.  A predicate with no clauses at all is looked up among the facts
    asserted into the world (actions and plain observations of the filter).
  - Comparisons accept a time-indexed random variable as an operand:
    `pos(1):t > 0` reads pos(1) at t first (the paper's shorthand).
  - Distribution sugar: `finite(P:V, ...)` (no list), `uniform(A, B)`
    (= contUniform(A, B), the paper's notation).  Parameters may be
    arithmetic expressions (`gaussian(X+3, 0.5)`).

## Semantics

Each world samples lazily only what the proofs need; every random variable
is drawn at most once per world (the store survives backtracking).  The
first clause (in file order) whose body holds defines a variable; if a
later clause for the same variable also holds in the same world, that is
an error naming both clauses (the original silently took the first), unless
the program declares `:- first_applicable(Name/Arity).` (or
`first_applicable(all)`) for decision lists such as learned rules.
Time-indexed variables: `h:0` and `h:t+1` clauses define h at time 0 /
t+1; `h:t` clauses are a fallback used only when no `h:0`/`h:t+1` clause
applies (the lazily-drawn "prior belief" of the original).  Nothing is
copied from t to t+1 implicitly: write `h:t+1 ~ val(V) := h:t ~= V` or
declare `:- persistent(Name/Arity).`, which adds exactly that clause
(`h:t+1 := h:t` for a derived atom) after the program's own ones.

Ground derived atoms whose proof uses true/1 or sample/2 are memoised per
world (success and failure), so such an atom has one truth value per world.

## Inference

Likelihood weighting with backward reasoning.  Evidence literals `h ~= v`
with ground h and v are not sampled but weighted by the density or mass of
h's applicable clause; evidence on a `val(V)` variable whose body computes
V by invertible arithmetic from another variable (`V is A*4.0`) is
propagated to that variable with the Jacobian (the original omitted it).
Other evidence (non-ground values, tests, atoms) is by rejection.  Ground
query literals `h ~= v` are weighted the same way (so `query(g ~= 0.0, P)`
on a continuous g returns a density).  As in the original, only samples
whose evidence weight has the fewest density factors count (a point mass
beats a density).

## Errors

A file that cannot be read (the engine's programs and the learner's
data alike: library ddc/lang/ddc_source) is an ISO error term whose
context names the file and line, `error(Formal,
context(ddc_source:source_terms/3, File:Line))`: existence_error(source_sink,
Spec) for no such file (a program named by the caller: context
`context(ddc_source:source_file/3, _)`), or an included one,
syntax_error(Msg) for a term that does not parse (syntax_error(too_deep(Max))
for brackets nested too deep), permission_error(include, source_sink, F)
for a file that includes itself, op/3's error for a bad `:- op/3`.

An error in what a program says (a clause, or a clause that misbehaves
when it runs) is `error(ddc(Cause, Where), _)` with Where = File:Line (or
`query`).  Causes: distribution(Dist, Why), non_ground_head(H),
overlapping_clauses(Key, OtherFile:OtherLine), zero_evidence(Evidence),
no_observation_clause(Obs), bad_directive(D), syntax_error(Msg) (of a
query's text).  print_message/2 renders both as `File:Line: cause`.

A misuse of the API is an ISO error term, its context the predicate and
what went wrong, `error(Formal, context(Module:Name/Arity, Message))`:
must_be/2's type_error/2, domain_error/2 and instantiation_error for bad
arguments; existence_error(ddc_filter, Filter) for a filter that was
freed or never made; existence_error(ddc_program, M) for a query on a
module that holds no program (M = current when none is loaded);
instantiation_error for a step's observation or action that is not
ground; domain_error(particle_indices(N), Indices) for resampling
indices that are not N indices in 0..N-1; permission_error(undo,
ddc_filter, Filter) for a second undo; type_error(number, X) for an
expectation of a value that is not a number.
*/

%!  ddc_load(+File) is det.
%!  ddc_load(+File, ?Module) is det.
%
%   Compile the DC program in File into Module (default: the absolute file
%   name) and make it the current program for query/2,3,4.  Replaces a
%   previous program of that module only if File compiles without error.
ddc_load(File) :-
    ddc_load(File, _).

ddc_load(Spec, M) :-
    resolve_file(Spec, File),
    (   var(M) -> M = File ; true ),
    with_mutex('$ddc_load',
               (   load_program(File, M),
                   set_current_program(M) )).

%!  ddc_program(-Module) is semidet.
%
%   The program loaded last.
ddc_program(M) :-
    current_program_(M), !.

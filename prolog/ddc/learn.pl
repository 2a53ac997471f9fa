/*  ddc/learn.pl (module ddc_learn, library(ddc/learn)) -- the Prolog side of
    the DC structure learner: groundings, candidate literals, partial
    possible worlds, learned clauses.

    The search itself (which literal to add, the leaves' statistical
    models, the score) runs in Python (python/probanchor/ddclearn/); it asks this
    module for the groundings of a target, the literals the declarative
    bias allows at a node of the tree, what each literal says of each
    grounding, and finally for the clauses of the tree in DC syntax.  The
    same predicates can be called by hand from swipl.

    This module loads a data set and checks its targets; the rest of its
    API lives in modules of one job each (in prolog/ddc/learn/), re-exported
    here:

      ddc_learn_nodes.pl       the tree's nodes: root, splits, groundings
      ddc_learn_candidates.pl  the literals the bias allows at a node
      ddc_learn_outcomes.pl    a literal's outcome in each row of a node
      ddc_learn_worlds.pl      proofs in partial possible worlds
      ddc_learn_clauses.pl     a leaf's clause, a target's tree clause
      ddc_learn_background.pl  the background knowledge learned clauses need
      ddc_learn_text.pl        DC source text of terms and clauses; names
      ddc_learn_scores.pl      scoring a DC program on data
*/

:- module(ddc_learn,
          [ learn_load/3,               % +Files, +Options, -Data
            learn_free/1,               % +Data
            learn_targets/2,            % +Data, -Targets
            learn_check/1,              % +Data
            learn_root/4,               % +Data, +Target, +Options, -Root
            learn_candidates/3,         % +Data, +Node, -Candidates
            learn_evaluate/4,           % +Data, +Node, +CandidateIds, -Outcomes
            learn_evaluate_rows/5,      % +Data, +Node, +CandidateId, +Rows, -Outcome
            learn_split/4,              % +Data, +Node, +CandidateId, -Children
            learn_forget/2,             % +Data, +Node
            learn_forget_rows/2,        % +Data, +Node
            learn_subset/4,             % +Data, +Node, +Rows, -Subset
            learn_clause/5,             % +Data, +Node, +Model, +Regressors, -Clause
            learn_clause_text/3,        % +Data, +Clause, -Text
            learn_leaf_text/5,          % +Data, +Node, +ModelText, +Regressors, -Texts
            learn_background_for/3,     % +Data, +Leaves, -Texts
            learn_tree_text/3,          % +Data, +Leaves, -Text
            learn_root_model/3,         % +Data, +Target, +ModelText
            learn_background/3,         % +Data, +Clauses, -Texts
            learn_groundings/3,         % +Data, +Node, -Groundings
            learn_program_scores/5      % +Data, +ProgramFile, +Targets, +Options, -Scores
          ]).

:- use_module(library(lists)).
:- use_module(library(apply)).
:- use_module(library(error)).
:- use_module(library(option)).
:- use_module('learn/ddc_learn_data').
:- use_module('learn/ddc_learn_text', [clause_names/3, term_text/3]).
:- use_module('learn/ddc_learn_candidates', [allowed_by_rank/4, literal_preds/2]).
:- use_module('learn/ddc_learn_nodes', [head_vars/5]).
:- reexport('learn/ddc_learn_nodes', [learn_root/4, learn_split/4, learn_forget/2, learn_forget_rows/2,
                              learn_subset/4, learn_groundings/3]).
:- reexport('learn/ddc_learn_candidates', [learn_candidates/3]).
:- reexport('learn/ddc_learn_outcomes', [learn_evaluate/4, learn_evaluate_rows/5]).
:- reexport('learn/ddc_learn_clauses', [learn_clause/5, learn_leaf_text/5, learn_background_for/3,
                                learn_tree_text/3, learn_root_model/3]).
:- reexport('learn/ddc_learn_background', [learn_background/3]).
:- reexport('learn/ddc_learn_text', [learn_clause_text/3]).
:- reexport('learn/ddc_learn_scores', [learn_program_scores/5]).

:- set_prolog_flag(optimise, true).

/** <module> The DC structure learner's groundings and clauses

A *node* of a tree is a set of groundings of the target's head: rows
row(Bindings, World), Bindings the values of the node's variables (the head's
key arguments, then the variables that relational literals on the path
introduced), World the partial possible world (an assoc Key-Value of the
uncertain facts the proofs on the path have read).  Python keeps each
row's weight and target value; nodes are stored here under an integer id
(ddc_learn_nodes.pl).

A *candidate* is a literal the bias allows at a node, instantiated (which
variables its + arguments take, which constants): one id per distinct
instance, shared by every node it appears at (ddc_learn_candidates.pl).
Its *outcome* for a row is a branch index and, for a continuous value,
the value (a regressor of the leaf's model; ddc_learn_outcomes.pl):

    | kind          | branches                                      |
    | discrete      | one per value of the domain, then undefined   |
    | numeric       | defined (value is a regressor), undefined     |
    | threshold     | one per interval, then undefined              |
    | test          | holds, does not hold                          |
    | count         | one (the count is a regressor)                |
    | agg_numeric   | defined (mean/max/min is a regressor), empty  |
    | agg_discrete  | one per value of the mode, then empty         |

A literal with new variables (`-` in a key argument) binds them to its
first solution, so that the clauses of a tree stay mutually exclusive
(DC's requirement): the clause says `(r(X, Y) ~= true -> true)`.

When a proof reads an uncertain fact that the row's world has not
assigned yet, the row is split into one row per value the fact may take
(a discrete distribution exactly, a continuous one by samples), weighted
by their probabilities, and proved again in each: the partial possible
worlds of section 4 of the paper, over which the leaves maximise the
expected log-likelihood (ddc_learn_worlds.pl).
*/

%!  learn_load(+Files:list, +Options:list, -Data:atom) is det.
%
%   Read data files (learn_data_load/3) and check that the targets can be
%   learned in some order (learn_check/1).  Options: targets(false) for
%   data to score a program on (learn_program_scores/5); seed(S) seeds the
%   samples of continuous uncertain facts; samples(N) (default 20) is how
%   many; max_worlds(K) (default 4096) bounds the partial worlds of one
%   grounding.
learn_load(Files, Options, M) :-
    learn_data_load(Files, Options, M),
    catch(( set_options(M, Options),
            ( option(targets(false), Options) -> true ; learn_check(M) ) ),
          E, ( learn_data_free(M), throw(E) )).

set_options(M, Options) :-
    option(samples(S), Options, 20),
    option(max_worlds(K), Options, 4096),
    must_be(positive_integer, S),
    must_be(positive_integer, K),
    (   option(seed(Seed), Options) -> set_random(seed(Seed)) ; true ),
    dynamic(M:'$ddcl_option'/2),
    retractall(M:'$ddcl_option'(_, _)),
    assertz(M:'$ddcl_option'(samples, S)),
    assertz(M:'$ddcl_option'(max_worlds, K)),
    maplist(declare(M), ['$ddcl_node'/3, '$ddcl_cand'/3, '$ddcl_counter'/2, '$ddcl_consts'/2,
                         '$ddcl_out'/3, '$ddcl_out_done'/1, '$ddcl_node_target'/1]).

declare(M, PI) :- dynamic(M:PI).

%!  learn_free(+Data) is det.
%
%   Forget a data set and everything learned about it (learn_data_free/1).
learn_free(M) :- learn_data_free(M).

%!  learn_targets(+Data, -Targets:list(dict)) is det.
%
%   One dict per target: name (the DC head, e.g. "occluded_by(A,O):t+1"),
%   predicate and arity (the internal predicate's name and key arity),
%   kind (discrete, continuous, count), domain (the values of a discrete
%   target), file and line (where it is declared).
learn_targets(M, Targets) :-
    learn_data_targets(M, Ts),
    maplist(target_dict(M), Ts, Targets).

target_dict(M, target(N, A, Spec, Names, File:Line), _{name: Text, predicate: N, arity: A,
                                                        kind: Kind, domain: Dom,
                                                        file: File, line: Line}) :-
    spec_kind(Spec, Kind, Dom),
    head_vars(M, N, A, Names, Vars),
    length(Vs, A), K =.. [N|Vs],
    dc_term(M, K, T),
    clause_names(Vars, Vs, Bs),
    term_text(T, Bs, Text).

spec_kind(discrete(D), discrete, D).
spec_kind(continuous, continuous, []).
spec_kind(count, count, []).

%!  learn_check(+Data) is det.
%
%   The targets read each other only in one direction: no target's modes
%   may reach back to it through other targets (the learned program would
%   be cyclic).
%
%   @error ddc_learn(cyclic_targets(Names), Where)
learn_check(M) :-
    findall(N, M:'$ddcl_target'(N, _, _, _), Ts),
    findall(T-U, ( member(T, Ts), member(U, Ts), U \== T, reads(M, T, U) ), Edges),
    (   member(T0, Ts), reaches(Edges, T0, T0, [T0], Cycle)
    ->  M:'$ddcl_target'(T0, _, _, W),
        throw(error(ddc_learn(cyclic_targets(Cycle), W), _))
    ;   true
    ).

reads(M, T, U) :-
    M:'$ddcl_mode'(_, T/_, _, C, L, _),
    allowed_by_rank(M, T, C, L),
    literal_preds((C, L), Ps), memberchk(U, Ps), !.

reaches(Edges, From, Goal, Seen, [From, To|Path]) :-
    member(From-To, Edges),
    (   To == Goal -> Path = []
    ;   \+ memberchk(To, Seen),
        reaches(Edges, To, Goal, [To|Seen], [To|Path])
    ).

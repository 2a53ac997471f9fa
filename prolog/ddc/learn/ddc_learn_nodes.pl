/*  ddc_learn_nodes.pl -- the nodes of the structure learner's trees: a
    target's root, the children of a split, the rows each node holds.
*/

:- module(ddc_learn_nodes,
          [ learn_root/4,               % +Data, +Target, +Options, -Root
            learn_split/4,              % +Data, +Node, +CandidateId, -Children
            learn_forget/2,             % +Data, +Node
            learn_forget_rows/2,        % +Data, +Node
            learn_subset/4,             % +Data, +Node, +Rows, -Subset
            learn_groundings/3,         % +Data, +Node, -Groundings
            target_examples/4,          % +Data, +Name, +KeyArity, -Keys
            target_value_goal/6,        % +Data, +Name, +KeyArity, -Key, -Value, -Goal
            head_vars/5                 % +Data, +Name, +KeyArity, +Names, -Vars
          ]).

:- use_module(library(lists)).
:- use_module(library(apply)).
:- use_module(library(assoc)).
:- use_module(library(pairs)).
:- use_module(library(error)).
:- use_module(ddc_learn_data).
:- use_module(ddc_learn_facts, [prob_table/2]).
:- use_module(ddc_learn_records).
:- use_module(ddc_learn_text, [type_var_base/2, unique_name/3]).
:- use_module(ddc_learn_worlds, [world_alternatives/6]).
:- use_module(ddc_learn_candidates, [next_id/3, branch_count/2]).
:- use_module(ddc_learn_outcomes, [node_outcomes/6, outcome_goal/5]).

:- set_prolog_flag(optimise, true).

/** <module> The nodes of the learner's trees

A node is stored in the data module as '$ddcl_node'(Id, Info, Rows):
Info is a node_info(Target, Vars, Used, Path) record (ddc_learn_records.pl:
its tree's target(Name, KeyArity, Spec), the node's variables v(Name,
Type), the candidates used on the path from the root, the path's steps
step(CandidateId, Branch)), Rows its groundings
row(Bindings, World) (see ddc/learn.pl).  The root of a target holds one
row per grounding of its head and partial world; a split gives each
branch of a candidate a child with the rows whose outcome is that
branch.
*/

                 /*******************************
                 *             ROOT             *
                 *******************************/

%!  learn_root(+Data, +Target:atom, +Options, -Root:dict) is det.
%
%   The root node of Target (its internal name, e.g. occluded_by_t1):
%   Root = _{node: Id, y: Ys, weight: Ws, example: Es}, one entry per row:
%   the target's value (a discrete one as its index in the domain), the
%   row's weight (1, or the probability of its partial world) and the
%   index of its example (the grounding of the head it comes from).
%
%   @error ddc_learn(target_without_facts(N/A), Where)
%   @error existence_error(ddc_learn_target, Target) if Data declares no
%          such target (learn_targets/2 lists them).
learn_root(M, N, _Options, _{node: Id, y: Ys, weight: Ws, example: Es}) :-
    learn_data_targets(M, Ts),
    (   memberchk(target(N, A, Spec, Names, W), Ts)
    ->  true
    ;   findall(T, member(target(T, _, _, _, _), Ts), Known),
        format(string(Msg), "its targets are ~q", [Known]),
        throw(error(existence_error(ddc_learn_target, N), context(learn_root/4, Msg)))
    ),
    head_vars(M, N, A, Names, Vars),
    target_examples(M, N, A, Keys),
    (   Keys == [] -> throw(error(ddc_learn(target_without_facts(N/A), W), _)) ; true ),
    empty_assoc(E0),
    target_value_goal(M, N, A, Ks, Y, Goal),
    retractall(M:'$ddcl_node_target'(_)), assertz(M:'$ddcl_node_target'(N)),
    foldl(root_rows(M, Spec, Ks, Goal, Y, E0), Keys, 0-Rows-Ys-Ws-Es, _-[]-[]-[]-[]),
    make_node_info([target(target(N, A, Spec)), vars(Vars), used([]), path([])], Info),
    new_node(M, Info, Rows, Id).

root_rows(M, Spec, Ks, Goal, Y, E0, Key, I0-Rows0-Ys0-Ws0-Es0, I-Rows-Ys-Ws-Es) :-
    I is I0+1,
    copy_term(Ks-Goal-Y, Key-G-Y1),
    M:'$ddcl_node_target'(N),
    K =.. [N|Key], example_weight(M, K, W),
    world_alternatives(M, G, Y1, E0, W, Alts),
    foldl(root_alternative(M, Spec, Key, I0), Alts, Rows0-Ys0-Ws0-Es0, Rows-Ys-Ws-Es).

root_alternative(M, Spec, Key, I, alternative(Y, World, F, _),
                 [row(Key, World)|Rows]-[YV|Ys]-[F|Ws]-[I|Es], Rows-Ys-Ws-Es) :-
    (   Y == '$none' -> throw(error(ddc_learn(no_value(Key), M), _)) ; true ),
    target_value(Spec, Y, M, Key, YV).

target_value(discrete(D), Y, M, Key, I) :- !,
    (   nth0(I0, D, Y0), Y0 == Y -> I = I0
    ;   throw(error(ddc_learn(value_not_in_domain(Key, Y, D, unknown), M), _))
    ).
target_value(_, Y, M, Key, Y1) :-
    (   number(Y) -> Y1 = Y
    ;   throw(error(ddc_learn(not_a_number(Key, Y), M), _))
    ).

%!  target_examples(+Data, +Name:atom, +KeyArity:integer, -Keys:list) is det.
%
%   The groundings of Name/KeyArity's key: the solutions of examples/2
%   when declared (a Boolean target given as atoms: an example without a
%   fact is false), else every key with a fact.
target_examples(M, N, A, Keys) :-
    (   M:'$ddcl_examples'(N/A, H0, G0, W)
    ->  internal_key(M, H0-G0, H-G1),
        dc_goal(M, G1, G, W),
        H =.. [_|Ks],
        findall(Ks, M:G, Keys0),
        list_to_set(Keys0, Keys)
    ;   length(Ks, A), append(Ks, [_], As), F =.. [N|As],
        findall(Ks, clause(M:F, true), K1),
        prob_table(N, PN), append(Ks, [_], PAs), PF =.. [PN|PAs],
        (   M:'$ddcl_prob_pred'(N, A) -> findall(Ks, clause(M:PF, true), K2) ; K2 = [] ),
        append(K1, K2, Keys)
    ).

%!  target_value_goal(+Data, +Name:atom, +KeyArity:integer, -Key:list,
%!                    -Value, -Goal) is det.
%
%   Goal, once the variables Key are bound to a grounding, binds Value to
%   the target's value in the data: false where examples/2 declares the
%   groundings and the grounding has no fact (a Boolean target given as
%   atoms), '$none' where it has none otherwise.
target_value_goal(M, N, A, Ks, Y, Goal) :-
    length(Ks, A), append(Ks, [V], As), TG =.. [N|As],
    (   M:'$ddcl_examples'(N/A, _, _, _) -> Missing = false ; Missing = '$none' ),
    Goal = ( once(M:TG) -> Y = V ; Y = Missing ).

%!  head_vars(+Data, +Name:atom, +KeyArity:integer, +Names:list,
%!            -Vars:list) is det.
%
%   The variables v(Name, Type) of a target's head: the names it was
%   written with, or names after the argument types.
head_vars(M, N, A, Names, Vars) :-
    (   M:'$ddcl_type'(N, A, Types, _, _) -> true
    ;   length(Types, A), maplist(=('_'), Types)
    ),
    foldl(head_var, Names, Types, []-[], Vars-_).

head_var(Name0, Type, Vars0-Used0, Vars-Used) :-
    (   Name0 \== '_' -> Base = Name0 ; type_var_base(Type, Base) ),
    unique_name(Base, Used0, Name),
    append(Vars0, [v(Name, Type)], Vars),
    Used = [Name|Used0].

                 /*******************************
                 *            SPLITS            *
                 *******************************/

%!  learn_split(+Data, +Node, +CandidateId, -Children:list(dict)) is det.
%
%   Split Node by a candidate: one child node per branch, each dict node
%   (its id), row (the parent rows its rows come from, in order), factor,
%   x.  A branch that binds new variables gives its child those variables.
learn_split(M, Node, Id, Children) :-
    M:'$ddcl_node'(Node, Info, Rows),
    M:'$ddcl_cand'(Id, _, Spec),
    branch_count(Spec, NB),
    outcome_goal(M, Spec, Bind, Goal, Out),
    length(Rows, NR), NR1 is NR-1,
    ( NR1 >= 0 -> numlist(0, NR1, Is) ; Is = [] ),
    pairs_keys_values(IRs, Is, Rows),
    node_outcomes(M, IRs, Bind, Goal, Out, Results),
    findall(B-(I-row(Bs1, W1)-F-X),
            ( member(row_result(I, Bs, W1, F, _, outcome(B, X, FVs)), Results),
              ( B =:= 0, FVs \== [] -> append(Bs, FVs, Bs1) ; Bs1 = Bs ) ),
            Pairs),
    NB1 is NB-1, numlist(0, NB1, BIs),
    node_info_target(Info, T),
    node_info_vars(Info, Vars),
    node_info_used(Info, Used),
    node_info_path(Info, Path),
    candidate_fresh(Spec, Fresh),
    maplist(child(M, T, Vars, Used, Path, Id, Fresh, Pairs), BIs, Children).

child(M, T, Vars, Used, Path, Id, Fresh, Pairs, B,
      _{node: C, branch: B, row: Rs, factor: Fs, x: Xs}) :-
    findall(R-I-F-X, member(B-(I-R-F-X), Pairs), Ls),
    findall(R, member(R-_-_-_, Ls), Rows),
    findall(I, member(_-I-_-_, Ls), Rs),
    findall(F, member(_-_-F-_, Ls), Fs),
    findall(X, member(_-_-_-X, Ls), Xs),
    (   B =:= 0, Fresh \== []
    ->  findall(Name, member(v(Name, _), Vars), Used0),
        foldl(fresh_var, Fresh, Vars-Used0, Vars1-_)
    ;   Vars1 = Vars
    ),
    append(Path, [step(Id, B)], Path1),
    make_node_info([target(T), vars(Vars1), used([Id|Used]), path(Path1)], Info1),
    new_node(M, Info1, Rows, C).

fresh_var(v(Type, _), S0, S) :-
    head_var('_', Type, S0, S).                 % a name after its type

new_node(M, Info, Rows, Id) :-
    next_id(M, node, Id),
    assertz(M:'$ddcl_node'(Id, Info, Rows)).

%!  learn_forget(+Data, +Node) is det.
%
%   Drop a node's rows (a branch the search did not keep, a lookahead).
learn_forget(M, Node) :-
    retractall(M:'$ddcl_node'(Node, _, _)).

%!  learn_forget_rows(+Data, +Node) is det.
%
%   Drop a node's rows but keep the node (its path): a node that was split
%   can still become a leaf, whose clause needs only its path.
learn_forget_rows(M, Node) :-
    (   retract(M:'$ddcl_node'(Node, Info, _))
    ->  assertz(M:'$ddcl_node'(Node, Info, []))
    ;   true
    ).

%!  learn_subset(+Data, +Node, +Rows:list(integer), -Subset:integer) is det.
%
%   A new node with Node's path and the rows of Node at the indices Rows
%   (from 0, in this order): a tree grown on some of the data, or other
%   data taken down a tree.
learn_subset(M, Node, Is, Id) :-
    must_be(list(nonneg), Is),
    M:'$ddcl_node'(Node, Info, Rows),
    msort(Is, Sorted),
    rows_at(Sorted, 0, Rows, Picked0),
    (   Is == Sorted -> Picked = Picked0
    ;   pairs_keys_values(Ps, Sorted, Picked0),
        list_to_assoc(Ps, Assoc),
        maplist(row_of(Assoc), Is, Picked)
    ),
    new_node(M, Info, Picked, Id).

row_of(Assoc, I, R) :- get_assoc(I, Assoc, R).

rows_at([], _, _, []) :- !.
rows_at([I|Is], K, [R|Rs], Out) :-
    (   I =:= K
    ->  Out = [R|Out1], rows_at(Is, K, [R|Rs], Out1)
    ;   K1 is K+1, rows_at([I|Is], K1, Rs, Out)
    ).

%!  learn_groundings(+Data, +Node, -Groundings:list) is det.
%
%   The node's rows as terms Head-World: the target's head with the row's
%   bindings and the partial world's assignment as Key=Value pairs (for
%   inspection from swipl).
learn_groundings(M, Node, Gs) :-
    M:'$ddcl_node'(Node, Info, Rows),
    node_info_target(Info, target(N, A, _)),
    findall(H-Ps, ( member(row(Bs, W), Rows), length(Ks, A), append(Ks, _, Bs),
                    K =.. [N|Ks], dc_term(M, K, H),
                    assoc_to_list(W, Ps0), maplist(world_pair(M), Ps0, Ps) ),
            Gs).

world_pair(M, Key-V, DK=V) :- dc_term(M, Key, DK).

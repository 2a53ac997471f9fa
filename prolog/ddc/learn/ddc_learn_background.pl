/*  ddc_learn_background.pl -- the background knowledge that learned
    clauses need, in DC syntax.
*/

:- module(ddc_learn_background,
          [ learn_background/3          % +Data, +Clauses, -Texts
          ]).

:- use_module(library(lists)).
:- use_module(library(apply)).
:- use_module(library(pairs)).
:- use_module(ddc_learn_data).
:- use_module(ddc_learn_text, [clause_text_vars/2, learn_clause_text/3]).
:- use_module(ddc_learn_candidates, [dc_literal/3]).

:- set_prolog_flag(optimise, true).

/** <module> Background knowledge of learned clauses

The data's DC clauses and derived predicates that the learned clauses'
bodies call, transitively, written back as they were read (their
time-indexed terms and variable names); a Prolog rule over the data's
random variables becomes a derived DC clause.
*/

%!  learn_background(+Data, +Clauses:list, -Texts:list(string)) is det.
%
%   The background knowledge the clauses need (the data's DC clauses and
%   derived predicates their bodies call, transitively), each in DC
%   syntax as a string: DreaML's Prolog rules over random variables become
%   derived DC clauses (`districtClientAccount(D, C, A) :=
%   clientDistrict(C, D) ~= true, hasAccount(C, A) ~= true.`).
learn_background(M, Clauses, Texts) :-
    findall(P, ( member(clause(C, _), Clauses), clause_calls(C, P) ), Ps0),
    sort(Ps0, Ps),
    background_closure(M, Ps, [], Needed),
    findall(W-T, ( member(N/A, Needed), functor(H, N, A),
                   M:'$ddcl_background'(H0, C, W), \+ H0 \= H,
                   background_text(M, C, W, T) ), WTs),
    sort(WTs, Sorted),
    pairs_values(Sorted, Texts).

clause_calls((_ ~ _ := B), P) :- body_pred(B, P).

body_pred(V, _) :- var(V), !, fail.
body_pred((A, B), P) :- !, ( body_pred(A, P) ; body_pred(B, P) ).
body_pred((A ; B), P) :- !, ( body_pred(A, P) ; body_pred(B, P) ).
body_pred((A -> B), P) :- !, ( body_pred(A, P) ; body_pred(B, P) ).
body_pred(\+ A, P) :- !, body_pred(A, P).
body_pred(findall_forward(_, G, _), P) :- !, body_pred(G, P).
body_pred(findall(_, G, _), P) :- !, body_pred(G, P).
body_pred(K ~= _, P) :- !, internal_name(K, P).
body_pred(G, P) :- callable(G), internal_name(G, P).

internal_name(X:TE, N/A) :- nonvar(TE), TE = T+1, T == t, !, functor(X, N0, A),
    atom_concat(N0, '_t1', N).
internal_name((X:T)+1, N/A) :- T == t, !, functor(X, N0, A), atom_concat(N0, '_t1', N).
internal_name(X:T, N/A) :- T == t, !, functor(X, N0, A), atom_concat(N0, '_t', N).
internal_name(G, N/A) :- functor(G, N, A).

background_closure(_, [], Acc, Acc).
background_closure(M, [P|Ps], Acc, Needed) :-
    (   memberchk(P, Acc)
    ->  background_closure(M, Ps, Acc, Needed)
    ;   P = N/A, functor(H, N, A),
        findall(Q, ( M:'$ddcl_background'(H0, C, _), \+ H0 \= H, background_calls(C, Q) ), Qs),
        (   M:'$ddcl_background'(H1, _, _), \+ H1 \= H -> Acc1 = [P|Acc] ; Acc1 = Acc ),
        append(Qs, Ps, Ps1),
        background_closure(M, Ps1, Acc1, Needed)
    ).

background_calls((_ ~ _ := B), Q) :- !, body_pred(B, Q).
background_calls((_ := B), Q) :- !, body_pred(B, Q).
background_calls((_ :- B), Q) :- !, body_pred(B, Q).

%   background_text(+M, +Clause, +Where, -Text): a DC clause as it was read
%   (its time-indexed terms and variable names back); a Prolog rule whose
%   body reads the data as a derived DC clause.
background_text(M, (H :- B), _, Text) :- !,
    (   reads_data(M, B)
    ->  internal_body_dc(M, B, DB), dc_term(M, H, DH),
        clause_text_vars((DH := DB), Text)
    ;   clause_text_vars((H :- B), Text)
    ).
background_text(M, C, W, Text) :-
    (   M:'$ddcl_named'(W, T-Vs) -> true ; T = C, Vs = [] ),
    undo_time(M, T, DC),
    learn_clause_text(M, clause(DC, Vs), Text).

%   undo_time(+M, +Term, -DC): every time-indexed term renamed for learning
%   (pos_t(A)) as it was written (pos(A):t).
undo_time(_, V, V) :- var(V), !.
undo_time(M, T0, T) :-
    compound(T0), !,
    compound_name_arguments(T0, N, As0),
    maplist(undo_time(M), As0, As),
    compound_name_arguments(T1, N, As),
    (   M:'$ddcl_timed'(N, _, _) -> dc_term(M, T1, T) ; T = T1 ).
undo_time(M, A, T) :-
    atom(A), M:'$ddcl_timed'(A, _, _), !, dc_term(M, A, T).
undo_time(_, T, T).

reads_data(M, B) :-
    body_pred(B, N/A),
    (   learn_data_pred(M, N, A, atom) -> true
    ;   A > 0, A1 is A-1, learn_data_pred(M, N, A1, rv(_))
    ), !.

internal_body_dc(M, (A, B), (DA, DB)) :- !, internal_body_dc(M, A, DA), internal_body_dc(M, B, DB).
internal_body_dc(M, (A ; B), (DA ; DB)) :- !, internal_body_dc(M, A, DA), internal_body_dc(M, B, DB).
internal_body_dc(M, (A -> B), (DA -> DB)) :- !, internal_body_dc(M, A, DA), internal_body_dc(M, B, DB).
internal_body_dc(M, \+ A, \+ DA) :- !, internal_body_dc(M, A, DA).
internal_body_dc(M, findall(T, G, L), findall_forward(T, DG, L)) :- !, internal_body_dc(M, G, DG).
internal_body_dc(M, G, DG) :- callable(G), !, dc_literal(M, G, DG).
internal_body_dc(_, G, G).

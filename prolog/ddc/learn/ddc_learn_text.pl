/*  ddc_learn_text.pl -- DC source text of the learner's terms and clauses,
    and the names of their variables.
*/

:- module(ddc_learn_text,
          [ learn_clause_text/3,        % +Data, +Clause, -Text
            clause_text_vars/2,         % +Clause, -Text
            term_text/3,                % +Term, +Bindings, -Text
            print_literal/1,            % +Literal
            print_conj/1,               % +Conjunction
            print_dc_term/1,              % +Term
            type_var_base/2,            % +Type, -Base
            capitalise/2,               % +Atom, -Capitalised
            unique_name/3,              % +Base, +Used, -Name
            clause_names/3,             % +Vars, +VarTerms, -Bindings
            new_var/4                   % +Base, ?Var, +Bindings0, -Bindings
          ]).

:- use_module(library(lists)).
:- use_module(library(apply)).
:- use_module(ddc_learn_data).

:- set_prolog_flag(optimise, true).

/** <module> DC text of learned terms

Terms are written with the DC operators of ddc_learn_data.pl, quoted,
their variables by the names in a list Name=Var (the others as `_`): a
clause's head and distribution on the first line, one body literal per
line.  Variable names come from the argument types (an obj is Obj, Obj1,
...).
*/

%!  new_var(+Base:atom, ?Var, +Names0:list, -Names:list) is det.
%
%   Names0 and Var named after Base, unique among Names0.
new_var(Base, V, Bs0, Bs) :-
    findall(N, member(N=_, Bs0), Used),
    unique_name(Base, Used, Name),
    append(Bs0, [Name=V], Bs).

                 /*******************************
                 *           PRINTING           *
                 *******************************/

%!  learn_clause_text(+Data, +Clause, -Text:string) is det.
%
%   Clause (from learn_clause/5) as DC source text: the head and its
%   distribution on the first line, one body literal per line.
learn_clause_text(_, clause(C, Bs), Text) :-
    copy_term(C-Bs, C1-Bs1),
    maplist([Name=V]>>( var(V) -> V = '$VAR'(Name) ; true ), Bs1),
    term_variables(C1, Rest),
    maplist(=('$VAR'('_')), Rest),
    with_output_to(string(Text), print_clause(C1)).

%!  clause_text_vars(+Clause, -Text:string) is det.
%
%   Clause as DC source text, its variables as A, B, ...
clause_text_vars(C, Text) :-
    copy_term(C, C1),
    numbervars(C1, 0, _),
    with_output_to(string(Text), print_clause(C1)).

%!  term_text(+Term, +Names:list, -Text:string) is det.
%
%   A literal as DC source text, its variables named by Names (Name=Var),
%   the others `_`.
term_text(T, Bs, Text) :-
    copy_term(T-Bs, T1-Bs1),
    maplist([Name=V]>>( var(V) -> V = '$VAR'(Name) ; true ), Bs1),
    term_variables(T1, Rest),
    maplist(=('$VAR'('_')), Rest),
    with_output_to(string(Text), print_literal(T1)).

print_clause((H ~ D := B)) :- !,
    print_literal(H), write(' ~ '), print_dc_term(D),
    (   B == true -> write('.')
    ;   write(' :='), print_body(B), write('.')
    ).
print_clause((H := B)) :- !,
    print_literal(H), write(' :='), print_body(B), write('.').
print_clause((H :- B)) :- !,
    print_dc_term(H), write(' :-'), print_body(B), write('.').
print_clause(C) :-
    print_dc_term(C), write('.').

print_body(B) :-
    conj_to_list(B, Ls),
    foldl([L, Sep0, ',']>>( write(Sep0), nl, write('    '), print_literal(L) ), Ls, '', _).

conj_to_list((A, B), Ls) :- !, conj_to_list(A, LA), conj_to_list(B, LB), append(LA, LB, Ls).
conj_to_list(A, [A]).

%!  print_literal(+Literal) is det.
%
%   Write a body literal in DC syntax (negations, if-then, comparisons
%   with their operators, findall_forward/3 with a conjunction).
print_literal(\+ G) :- !, write('\\+ '), print_literal(G).
print_literal((A -> B ; C)) :- !,
    write('('), print_literal(A), write(' -> '), print_conj(B), write(' ; '), print_conj(C),
    write(')').
print_literal((A -> B)) :- !, write('('), print_literal(A), write(' -> '), print_literal(B), write(')').
print_literal((A, B)) :- !, write('('), print_conj((A, B)), write(')').
print_literal(findall_forward(T, G, L)) :- !,
    write('findall_forward('), print_dc_term(T), write(', '), print_literal(G),
    write(', '), print_dc_term(L), write(')').
print_literal(G) :-
    compound(G), G =.. [Op, A, B], memberchk(Op, [~=, <, >, =<, >=, ==, is, =, =:=, =\=]), !,
    print_dc_term(A, 699), format(' ~w ', [Op]), print_dc_term(B, 699).
print_literal(G) :- print_dc_term(G).

%!  print_conj(+Conjunction) is det.
%
%   Write a conjunction of literals, separated by commas.
print_conj((A, B)) :- !, print_literal(A), write(', '), print_conj(B).
print_conj(A) :- print_literal(A).

%!  print_dc_term(+Term) is det.
%
%   Write a term quoted, with the DC operators.
print_dc_term(T) :-
    print_dc_term(T, 1200).

print_dc_term(T, Priority) :-
    write_term(T, [quoted(true), numbervars(true), spacing(next_argument),
                   module(ddc_learn_data), priority(Priority)]).

                 /*******************************
                 *            NAMES             *
                 *******************************/

%!  type_var_base(+Type, -Base:atom) is det.
%
%   Variables of type obj are Obj, Obj1, ...; of DreaML's type la are La,
%   ...; of an untyped argument X.
type_var_base(T, B) :-
    (   atom(T), T \== '_', T \== '' -> capitalise(T, B0), sanitise(B0, B)
    ;   B = 'X'
    ).

%!  capitalise(+Atom, -Capitalised:atom) is det.
%
%   Atom with its first letter in upper case.
capitalise(A, C) :-
    atom_codes(A, [F|Rest]),
    code_type(U, to_upper(F)),
    atom_codes(C, [U|Rest]).

sanitise(A, S) :-
    atom_codes(A, Cs),
    include([C]>>( code_type(C, csym) ), Cs, Cs1),
    ( Cs1 == [] -> S = 'X' ; atom_codes(S, Cs1) ).

%!  unique_name(+Base:atom, +Used:list(atom), -Name:atom) is det.
%
%   Base, or Base1, Base2, ..., the first not in Used.
unique_name(Base, Used, Name) :-
    (   \+ memberchk(Base, Used) -> Name = Base
    ;   between(1, inf, I), atom_concat(Base, I, Name), \+ memberchk(Name, Used) -> true
    ).

%!  clause_names(+Vars:list, +VarTerms:list, -Names:list) is det.
%
%   Name=Var for the node's variables v(Name, Type) and their terms.
clause_names(Vars, Terms, Bs) :-
    length(Vars, N), length(Ts, N), append(Ts, _, Terms),
    maplist([v(Name, _), T, Name=T]>>true, Vars, Ts, Bs).

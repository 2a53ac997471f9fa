/** <module> The DC programs loaded into modules

Part of the DDC system (ddc.pl is the module users load).  Loads a
program file (read by ddc_read.pl, compiled by ddc_compile.pl) into a
module of its own, atomically: a program with an error leaves the
module as it was.  Keeps which file each program module holds and
which program was loaded last.
*/

:- module(ddc_programs,
          [ load_program/2,             % +File, +Module
            set_current_program/1,      % +Module
            unload_program/1,           % +Module
            program_items/2,            % +Module, -Items
            program_file_/2,            % ?Module, ?File
            current_program_/1,         % ?Module
            optimised/1                 % :Goal
          ]).

:- use_module(library(lists)).
:- use_module(library(error)).
:- use_module(ddc_records).
:- use_module(ddc_read).
:- use_module(ddc_body).
:- use_module(ddc_compile).

%   Arithmetic compiled to virtual-machine instructions (local to this
%   file; see ddc.pl).
:- set_prolog_flag(optimise, true).

%!  current_program_(?Module) is semidet.
%
%   Module holds the program loaded last (ddc_load/1,2).
%!  program_file_(?Module, ?File) is nondet.
%
%   Module holds the program read from File.
:- dynamic
    current_program_/1,
    program_file_/2.

%!  set_current_program(+Module) is det.
%
%   Module holds the program that query/2,3,4 read by default.
set_current_program(M) :-
    with_mutex('$ddc_load',
               (   retractall(current_program_(_)),
                   assertz(current_program_(M)) )).

%!  load_program(+File:atom, +Module:atom) is det.
%
%   Reads and compiles the DC program in File (an absolute file name) and
%   installs it into Module, replacing what Module held only if File
%   compiles without error.  Loads run one at a time (mutex '$ddc_load'):
%   two threads loading into one module do not interleave their clauses.
%   A filter's program is loaded into a module of the filter's own
%   (filter_new/5), which no later load replaces.
load_program(File, M) :-
    must_be(atom, File),
    must_be(atom, M),
    with_mutex('$ddc_load',
               (   read_program(File, Items),
                   compile_program(File, M, Items, Clauses, Info),
                   install_program(M, File, Clauses, Info) )).

%!  unload_program(+Module:atom) is det.
%
%   Removes the program loaded into Module (its predicates and its file).
unload_program(M) :-
    must_be(atom, M),
    with_mutex('$ddc_load',
               (   clear_program_module(M),
                   retractall(program_file_(M, _)),
                   retractall(current_program_(M)) )).


%!  program_items(+Module, -Items) is det.
%
%   The classified items of the program
%   loaded into Module (with the clauses its persistent/1 directives add,
%   and rivals(Id, R) for each random variable clause: whether a later
%   clause can define what it defines, see rivals/3 in
%   ddc_compile.pl), as the batched filter
%   reads them (ddc_batch.pl); kept by compile_program/5.
program_items(M, Items) :-
    M:'$ddc_items'(Items).

install_program(M, File, Clauses, Info) :-
    clear_program_module(M),
    set_module(M:base(user)),
    set_module(M:class(user)),
    declare_program_preds(M, Info),
    optimised(forall(member(C, Clauses), install_clause(M, C))),
    assertz(M:'$ddc_info'(Info)),
    retractall(program_file_(M, _)),
    assertz(program_file_(M, File)).

%   install_clause(+Module, +Clause): a clause compiled from a line of the
%   program ('$at'(Line, C)) is kept with that line, so that an error at
%   run time names it (program_error/4).
install_clause(M, '$at'(L, C)) :- !,
    assertz(M:C, Ref),
    assertz(M:'$clause_line'(Ref, L)).
install_clause(M, C) :-
    assertz(M:C).

%   clear_program_module(+M): the predicates of a program module gone.
clear_program_module(M) :-
    (   current_module(M), M \== user, M \== ddc, M \== system
    ->  forall(( current_predicate(M:N/A), functor(H, N, A),
                 \+ predicate_property(M:H, imported_from(_)) ),
               abolish(M:N/A))
    ;   true
    ).

%!  optimised(:Goal) is semidet.
%
%   Goal (asserting clauses) with arithmetic compiled inline, as in this
%   file; the caller's flag is restored.
:- meta_predicate optimised(0).
optimised(Goal) :-
    current_prolog_flag(optimise, Old),
    setup_call_cleanup(set_prolog_flag(optimise, true), Goal,
                       set_prolog_flag(optimise, Old)).

declare_program_preds(M, Info) :-
    info_derived_untimed(Info, DerU), info_derived_timed(Info, DerT),
    dynamic(M:'$rv'/9),
    dynamic(M:'$rv_pos'/3),
    dynamic(M:'$clause_line'/2),
    dynamic(M:'$ddc_info'/1),
    dynamic(M:'$ddc_items'/1),
    dynamic(M:'$ddc_tmp'/4),
    dynamic(M:'$sweep'/4),
    dynamic(M:'$sweep_key'/4),
    forall(member(N/A, DerU),
           ( A1 is A+1, derived_name(N, d, DN), dynamic(M:DN/A1),
             derived_name(N, d0, DN0), dynamic(M:DN0/A1),
             derived_name(N, ds, DNS), dynamic(M:DNS/A1) )),
    forall(member(N/A, DerT),
           ( A2 is A+2,
             forall(member(K, [dt, dt0, dt1, dt2, dts]),
                    ( derived_name(N, K, DN), dynamic(M:DN/A2) )) )).

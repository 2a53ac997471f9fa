/*  ddc_nesting.pl -- the bracket depth of program and term texts, checked before they are read.

    SWI-Prolog's reader parses arguments and parenthesised terms by recursion on the C
    stack.  Inside an embedding process (Python through janus) its C-stack guard does not
    hold, and a text nested 15,000-20,000 brackets deep ends the process with a
    segmentation fault.  Every text the engine reads from a user (a program file, a query,
    an observation) is first scanned here: deeper than max_nesting/1 is an error naming the
    file and line, before the reader sees it (ddc_source.pl for files).
*/

:- module(ddc_nesting,
          [ max_nesting/1,              % -Depth
            file_too_deep/3,            % +File, -Max, -Line
            check_text_nesting/2        % +Text, +Where
          ]).

:- use_module(library(error)).
:- use_module(library(readutil)).

/** <module> Bracket depth of texts before they are read

Brackets are `(`, `[` and `{`; those inside quoted atoms, strings, back-quoted texts, `0'c`
character codes and comments do not count.  Long lists, long operator chains and prefix
operators are read without recursion and are not limited here.
*/

%!  max_nesting(-Depth:integer) is det.
%
%   The deepest bracket nesting the engine reads (10,000: the reader inside janus was seen
%   to crash between 15,000 and 20,000).
max_nesting(10000).

%!  file_too_deep(+File:atom, -Max:integer, -Line:integer) is semidet.
%
%   File nests brackets deeper than Max (max_nesting/1), first on Line; fails if it does
%   not.  The reader of DC files (ddc_source.pl) calls it before it reads a file.
file_too_deep(File, Max, Line) :-
    must_be(atom, File),
    read_file_to_string(File, Text, []),
    max_nesting(Max),
    open_brackets(Text, Opens),
    Opens > Max,                            % (else it cannot nest deeper: no scan)
    string_codes(Text, Codes),
    too_deep(Codes, Max, Line).

%   open_brackets(+Text, -N): how many opening brackets Text holds, quoted or not.
open_brackets(Text, N) :-
    split_string(Text, "([{", "", Parts),
    length(Parts, K),
    N is K - 1.

%!  check_text_nesting(+Text, +Where) is det.
%
%   Text (a string or an atom) nests brackets at most max_nesting/1 deep.  Texts shorter
%   than twice the limit cannot be deeper and are not scanned.
%
%   @error ddc(too_deep(Max), Where) otherwise.
check_text_nesting(Text, Where) :-
    max_nesting(Max),
    (   ( string(Text) -> string_length(Text, Len) ; atom_length(Text, Len) ),
        Len > 2*Max,
        string_codes(Text, Codes),
        too_deep(Codes, Max, _)
    ->  throw(error(ddc(too_deep(Max), Where), _))
    ;   true
    ).

%   too_deep(+Codes, +Max, -Line): the brackets of Codes nest deeper than Max, first on
%   Line.  A scanner with one state per kind of text: code (c), quoted with ' " ` (q(Q)),
%   a line comment (lc) and a block comment (bc).
too_deep(Codes, Max, Line) :-
    scan(Codes, c, 0, Max, 1, Line).

scan([], _, _, _, _, _) :- !, fail.
scan([C|Cs], S, D, Max, L0, L) :-
    (   C == 0'\n -> L1 is L0+1 ; L1 = L0 ),
    step(S, C, Cs, S1, Cs1, D, D1),
    (   D1 > Max
    ->  L = L1
    ;   scan(Cs1, S1, D1, Max, L1, L)
    ).

step(c, C, Cs, S, Cs1, D, D1) :- !, code_step(C, Cs, S, Cs1, D, D1).
step(q(Q), C, Cs, S, Cs1, D, D) :- !,
    (   C == 0'\\, Cs = [_|Cs2] -> S = q(Q), Cs1 = Cs2
    ;   C == Q -> S = c, Cs1 = Cs
    ;   S = q(Q), Cs1 = Cs
    ).
step(lc, C, Cs, S, Cs, D, D) :- !,
    ( C == 0'\n -> S = c ; S = lc ).
step(bc, C, Cs, S, Cs1, D, D) :-
    (   C == 0'*, Cs = [0'/|Cs2] -> S = c, Cs1 = Cs2
    ;   S = bc, Cs1 = Cs
    ).

code_step(C, Cs, c, Cs, D, D1) :- open_bracket(C), !, D1 is D+1.
code_step(C, Cs, c, Cs, D, D1) :- close_bracket(C), !, D1 is max(0, D-1).
code_step(0'%, Cs, lc, Cs, D, D) :- !.
code_step(0'/, [0'*|Cs], bc, Cs, D, D) :- !.
code_step(0'0, [0''|Cs], c, Cs1, D, D) :- !,      % 0'c, 0'\n, 0''' (a character code)
    (   Cs = [0'\\, _|Cs1] -> true
    ;   Cs = [0'', 0''|Cs1] -> true
    ;   Cs = [_|Cs1] -> true
    ;   Cs1 = []
    ).
code_step(C, Cs, q(C), Cs, D, D) :- quote(C), !.
code_step(_, Cs, c, Cs, D, D).

open_bracket(0'().
open_bracket(0'[).
open_bracket(0'{).

close_bracket(0')).
close_bracket(0']).
close_bracket(0'}).

quote(0'').
quote(0'").
quote(0'`).

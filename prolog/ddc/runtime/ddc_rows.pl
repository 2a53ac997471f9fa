/** <module> A filter's values as rows of floats

Part of the DDC system (ddc.pl is the module users load): the row code
of filter_rows/6, used by the filter API (ddc_filter.pl) on the values
of any engine and by the per-particle engine on its stores.
*/

:- module(ddc_rows,
          [ values_rows/4,              % +Values, -Width, -Floats, -Others
            row_width/2,                % +Value, -Width
            float_row/4,                % +Value, +Width, -Floats, ?Tail
            nan_row/3                   % +Width, -Floats, ?Tail
          ]).

:- use_module(library(lists)).

%   Arithmetic compiled to virtual-machine instructions (local to this
%   file; see ddc.pl).
:- set_prolog_flag(optimise, true).

%!  values_rows(+Values, -Width, -Floats, -Others) is det.
%
%   Values: for each particle value(V) or none.  If every V is a number or
%   a tuple (A, B, ...) of numbers of the same length Width, Floats is one
%   flat list of N*Width floats, particle by particle (a row of NaNs for
%   none), and Others = []; else Width = 0, Floats = [] and Others =
%   Values.
values_rows(Values, Width, Floats, Others) :-
    (   once(member(value(V1), Values)),
        row_width(V1, Width1),
        value_rows(Values, Width1, Floats1)
    ->  Width = Width1, Floats = Floats1, Others = []
    ;   Width = 0, Floats = [], Others = Values
    ).

value_rows([], _, []).
value_rows([V|Vs], W, Fs) :-
    (   V = value(X)
    ->  float_row(X, W, Fs, Fs1)
    ;   nan_row(W, Fs, Fs1)
    ),
    value_rows(Vs, W, Fs1).

%!  row_width(+Value, -Width) is semidet.
%
%   Value is a number (Width 1) or a tuple (A, B, ...) of Width numbers.
row_width(V, 1) :- number(V), !.
row_width((A, B), W) :- number(A), row_width(B, W0), W is W0+1.

%!  nan_row(+Width, -Floats, ?Tail) is det.
%
%   Floats is Width NaNs followed by Tail.
nan_row(0, Fs, Fs) :- !.
nan_row(W, [X|Fs], Fs1) :-
    X is nan,
    W1 is W-1,
    nan_row(W1, Fs, Fs1).

%!  float_row(+Value, +Width, -Floats, ?Tail) is semidet.
%
%   Floats is Value's Width numbers as floats followed by Tail; fails if
%   Value is not a row of that width.
float_row(V, 1, [X|Fs], Fs) :-
    number(V), !,
    X is float(V).
float_row((A, B), W, [X|Fs], Fs1) :-
    W > 1, number(A),
    X is float(A),
    W1 is W-1,
    float_row(B, W1, Fs, Fs1).

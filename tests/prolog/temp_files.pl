/*  temp_files.pl -- a helper of the plunit tests that read DC files: files written into a
    new temporary folder, and their absolute paths.
*/
:- module(temp_files, [files/2, path/3]).
:- use_module(library(lists)).
:- use_module(library(filesex)).

%!  files(+Files:list(pair), -Dir:atom) is det.
%
%   The files Name-Lines (Name relative, sub-folders made as needed; each line written as
%   by ~w) in a new temporary folder Dir.
files(Files, Dir) :-
    tmp_file(dc_files, Dir),
    make_directory(Dir),
    forall(member(Name-Lines, Files),
           (   directory_file_path(Dir, Name, Path),
               file_directory_name(Path, Sub), make_directory_path(Sub),
               setup_call_cleanup(open(Path, write, S),
                                  forall(member(L, Lines), format(S, "~w~n", [L])),
                                  close(S)) )).

%!  path(+Dir:atom, +Name:atom, -Path:atom) is det.
%
%   The absolute path of file Name in Dir.
path(Dir, Name, Path) :-
    directory_file_path(Dir, Name, Path0),
    absolute_file_name(Path0, Path).

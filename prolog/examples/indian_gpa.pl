% The Indian GPA problem (the original's indian-gpa.pl), restated: a
% student's GPA is either American (0..4) or Indian (0..10); each scale has
% point masses at its ends and a continuous (beta) part in between.
coin ~ finite([0.95:true, 0.05:false]).
agpa ~ beta(8, 2) := coin ~= true.
american_gpa ~ finite([0.85:4.0, 0.15:0.0]) := coin ~= false.
american_gpa ~ val(V) := coin ~= true, agpa ~= A, V is A*4.0.

coin2 ~ finite([0.99:true, 0.01:false]).
igpa ~ beta(5, 5) := coin2 ~= true.
indian_gpa ~ finite([0.1:0.0, 0.9:10.0]) := coin2 ~= false.
indian_gpa ~ val(V) := coin2 ~= true, igpa ~= A, V is A*10.0.

nation ~ finite([0.25:a, 0.75:i]).
student_gpa ~ val(A) := nation ~= a, american_gpa ~= A.
student_gpa ~ val(A) := nation ~= i, indian_gpa ~= A.

from bridge import terms  # noqa: E402,F401  (Python value -> Prolog term text)
from bridge.filter import Filter, FilterError, StepResult, ZeroWeightWarning  # noqa: E402,F401
from bridge.program import DDCError, Program, QueryResult, load  # noqa: E402,F401

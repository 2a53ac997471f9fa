from bridge import terms  # noqa: E402,F401  (Python value -> Prolog term text)
from bridge.filter import (  # noqa: E402,F401
    DEFAULT_THREADS,
    Filter,
    FilterError,
    StepResult,
    ZeroWeightWarning,
)
from bridge.program import DDCError, Program, QueryResult, load  # noqa: E402,F401

"""What scripts/mutants_py.py mutates: the target modules with their tests, and the operators."""

from __future__ import annotations

import re
from dataclasses import dataclass


@dataclass(frozen=True)
class Target:
    """A module to mutate: the definitions in scope (all when empty) and its tests (pytest's
    arguments: files, and a ``-k`` selection)."""

    path: str
    tests: tuple[str, ...]
    scope: tuple[str, ...] = ()


#: The verdict and metric code, each with the tests that check it (the module's own
#: doctests are run too). A mutant is tested against these only.
TARGETS = (
    Target(
        "python/famcc/verdicts/verdict.py", ("tests/test_verdicts.py", "tests/test_own_runs.py")
    ),
    Target("python/famcc/verdicts/claims.py", ("tests/test_verdicts.py", "tests/test_own_runs.py")),
    Target(
        "python/famcc/scenarios.py",
        ("tests/test_verdicts.py",),
        ("Scenario.recovery_bound", "Scenario.verdicts", "Scenario.claims", "Scenario.check"),
    ),
    Target(
        "python/famcc/metrics.py",
        ("tests/test_simulate.py", "tests/test_verdicts.py", "tests/test_own_runs.py"),
    ),
    Target("python/famcc/tuning/assess.py", ("tests/test_tuning.py",)),
    Target("python/famcc/campaigns/stats.py", ("tests/test_campaign.py",)),
    # test_reproduce.py's other tests run `famcc reproduce`, which uses no code of the sweep.
    *(
        Target(
            f"python/famcc/sweep/{m}.py",
            ("tests/test_reproduce.py", "-k", "sweep or limits or xi_text"),
        )
        for m in ("run", "tables", "answer", "report")
    ),
)

#: cosmic-ray operators kept: the plausible slips. Left out: arithmetic turned
#: into shifts, bit operations, powers or modulo (type errors or noise), the
#: comparisons turned into identity tests and back, removed decorators, and
#: the unary operators other than dropping a minus, a not or a ~.
OPERATORS = re.compile(
    r"core/("
    r"ReplaceBinaryOperator_\w+_(Add|Sub|Mul|Div)"
    r"|ReplaceBinaryOperator_(BitAnd_BitOr|BitOr_BitAnd)"
    r"|ReplaceComparisonOperator_(Eq_NotEq|NotEq_Eq|Is_IsNot|IsNot_Is)"
    r"|ReplaceComparisonOperator_(Lt_LtE|LtE_Lt|Gt_GtE|GtE_Gt)"
    r"|ReplaceComparisonOperator_(Lt_Gt|Gt_Lt|LtE_GtE|GtE_LtE)"
    r"|ReplaceComparisonOperator_(Lt_GtE|GtE_Lt|LtE_Gt|Gt_LtE)"
    r"|ReplaceUnaryOperator_Delete_(USub|Not|Invert)"
    r"|AddNot|ReplaceTrueWithFalse|ReplaceFalseWithTrue|ReplaceAndWithOr|ReplaceOrWithAnd"
    r"|ReplaceBreakWithContinue|ReplaceContinueWithBreak|NumberReplacer|ZeroIterationForLoop"
    r"|ExceptionReplacer"
    r")$"
)

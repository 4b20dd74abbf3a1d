"""The firmware check's target verdict (scripts/fw_target.sh): a missed or
unmeasured target fails the check, a met one does not."""

import subprocess
from pathlib import Path

SCRIPT = Path(__file__).resolve().parent.parent / "scripts" / "fw_target.sh"


def verdict(value: str, limit: str) -> tuple[str, int]:
    """The printed line and the number of failures after one `target` call."""
    out = subprocess.run(
        [
            "bash",
            "-c",
            f'FAILURES=(); source "{SCRIPT}"; target flash "{value}" {limit}; echo "${{#FAILURES[@]}}"',
        ],
        check=True,
        capture_output=True,
        text=True,
    ).stdout.splitlines()
    return out[0].strip(), int(out[1])


def test_a_met_target_passes() -> None:
    assert verdict("14184", "16384") == ("met     flash: 14184 <= 16384", 0)
    assert verdict("16384", "16384")[1] == 0


def test_a_missed_target_fails_the_check() -> None:
    line, failures = verdict("25700", "16384")
    assert line.startswith("MISSED") and failures == 1


def test_a_target_not_measured_fails_the_check() -> None:
    line, failures = verdict("", "16384")
    assert "not measured" in line and failures == 1


def test_fractional_values_compare_as_numbers() -> None:
    assert verdict("354.6", "1500")[1] == 0
    assert verdict("1500.1", "1500")[1] == 1

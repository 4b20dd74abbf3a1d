"""The views of a run besides its figure: the Jupyter HTML and the data frame."""

from __future__ import annotations

import html
import importlib
from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:
    from famcc.sim.result import SimResult


def text_view(self: SimResult) -> str:
    """The run's header and its summary in plain words (``repr(SimResult)``)."""
    out = self.output.name + self.output.bracket()
    inp = self.input.name + self.input.bracket()
    t_end = float(self.t[-1]) if len(self.t) else 0.0
    head = (
        f"<famcc.SimResult: {len(self.t)} samples, 0-{t_end:g} s at dt = {self.dt:g} s; "
        f"output {out}, input {inp}"
    )
    ctrl = f" controller: {self.controller_description}"
    if self.reference_repr:
        ctrl += f"; reference {self.reference_repr}"
    body = [" " + line for line in self.summary().text.splitlines()]
    return "\n".join([head, ctrl, *body]) + ">"


def png(self: SimResult) -> bytes:
    """The run's figure as PNG at 72 dpi (``SimResult._repr_png_``)."""
    import io

    buf = io.BytesIO()
    self.plot().savefig(buf, format="png", dpi=72)
    return buf.getvalue()


def html_view(self: SimResult) -> str:
    """The summary as a table and the figure (``SimResult._repr_html_``)."""
    import base64

    s = self.summary()
    rows = "".join(
        f"<tr><th style='text-align:left'>{html.escape(k)}</th>"
        f"<td style='text-align:left'>{html.escape(_cell(v))}</td></tr>"
        for k, v in s.items()
        if v is not None
    )
    head = html.escape(repr(self).splitlines()[0].lstrip("<"))
    ctrl = html.escape(self.controller_description)
    png = base64.b64encode(self._repr_png_()).decode("ascii")
    notes = "".join(f"<li>{html.escape(line)}</li>" for line in s.text.splitlines())
    return (
        f"<div><p><b>{head}</b><br>controller: {ctrl}</p><ul>{notes}</ul>"
        f"<details><summary>metrics</summary><table>{rows}</table></details>"
        f"<img src='data:image/png;base64,{png}' style='max-width:100%'/></div>"
    )


def dataframe(self: SimResult) -> Any:
    """The recorded arrays as a pandas DataFrame indexed by time (``SimResult.to_dataframe``).

    Columns: ``y``, ``y_d``, ``x1..xn``, ``z1..zn``, ``v``, ``u``,
    ``saturated`` and, when recorded, ``z_hat1..z_hatn``, ``xi``,
    ``xi_nominal``, ``s``, ``s_prev``, ``ds_prev``, ``bound_x``, ``bound_y``,
    ``nominal_bound_x``, ``nominal_bound_y``, ``expanded``, ``expansion`` and
    ``neg_f_over_g``. ``df.attrs`` holds the names and units.

    Raises
    ------
    ImportError
        When pandas is not installed (it is optional: ``pip install pandas``).
    """
    try:
        pd: Any = importlib.import_module("pandas")
    except ImportError as exc:
        raise ImportError(
            "SimResult.to_dataframe() needs pandas, which famcc does not require: "
            "pip install pandas"
        ) from exc
    n = self.z.shape[1]
    cols: dict[str, Any] = {"y": self.y, "y_d": self.y_d}
    cols.update({f"x{i + 1}": self.x[:, i] for i in range(self.x.shape[1])})
    cols.update({f"z{i + 1}": self.z[:, i] for i in range(n)})
    if self.z_hat is not None:
        cols.update({f"z_hat{i + 1}": self.z_hat[:, i] for i in range(n)})
    cols.update({"v": self.v, "u": self.u, "saturated": self.saturated})
    for name in ("xi", "xi_nominal", "s", "s_prev", "ds_prev"):
        if getattr(self, name) is not None:
            cols[name] = getattr(self, name)
    for name, arr in (("bound", self.bounds), ("nominal_bound", self.nominal_bounds)):
        if arr is not None:
            cols[f"{name}_x"], cols[f"{name}_y"] = arr[:, 0], arr[:, 1]
    for name in ("expanded", "expansion", "neg_f_over_g"):
        if getattr(self, name) is not None:
            cols[name] = getattr(self, name)
    df = pd.DataFrame(cols, index=pd.Index(self.t, name="t"))
    df.attrs.update(
        output=(self.output.name, self.output.unit),
        input=(self.input.name, self.input.unit),
        dt=self.dt,
        u_limits=self.u_limits,
    )
    return df


def _cell(v: Any) -> str:
    return f"{v:.4g}" if isinstance(v, float) else str(v)

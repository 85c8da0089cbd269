"""The ``[stock]`` table: the blank a disc cam is cut from.

```toml
[stock]
kind = "round"         # a bar or disc blank, centred on the cam axis
diameter = 124.0       # mm
top_allowance = 0.0    # mm of face stock above Z0 (not faced by the program: the report states it)

# or a flame-cut / pre-profiled blank:
# kind = "offset"
# allowance = 3.0      # mm over the finished profile, everywhere
```

Without ``[stock]`` the blank is round, 2 mm over the cam's largest radius
(:data:`DEFAULT_STOCK`), and the report says so.  Whether the blank is big
enough is known only once the cam is built: :func:`camcam.nc.stock.blank_for`
checks it.
"""

from __future__ import annotations

from camcam.nc.settings import DEFAULT_OVERSIZE_MM, DEFAULT_STOCK, STOCK_KINDS, StockSpec
from camcam.spec.reader import Table

__all__ = ["StockSpec", "read_stock", "DEFAULT_STOCK", "DEFAULT_OVERSIZE_MM", "STOCK_KINDS"]

def read_stock(t: Table, cam=None) -> StockSpec:
    """Validate ``[stock]`` (the size against the cam is checked by the NC stage).

    ``cam`` (the validated ``[cam]``, if any): a stock table needs a disc cam,
    and a face-groove cam's blank is round.
    """
    kind = t.string("kind", "round", choices=STOCK_KINDS)
    if cam is not None and cam.kind == "cylindrical":
        raise t.error("kind", "a [stock] table applies to disc cams; a cylindrical cam's blank is its cylinder")
    if cam is not None and cam.kind == "disc-groove" and kind == "offset":
        raise t.error("kind", '"offset" needs an open disc cam; a face-groove cam is cut from a round blank')
    diameter = allowance = None
    if kind == "round":
        diameter = t.number("diameter", minimum=0.0, inclusive=False, unit="mm")
    else:
        allowance = t.number("allowance", minimum=0.0, inclusive=False, unit="mm")
    top = t.number("top_allowance", 0.0, minimum=0.0, unit="mm")
    t.done()
    return StockSpec(kind=kind, diameter_mm=diameter, allowance_mm=allowance, top_allowance_mm=top, stated=True)

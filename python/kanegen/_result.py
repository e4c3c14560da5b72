# SPDX-License-Identifier: GPL-2.0-or-later
"""The result of Model.simulate: the driver's CSV as NumPy columns."""

import io

import numpy


class SimulationResult:
    """A simulation's samples: .t, .columns (names), .data (2-D, one row per
    sample), result["q0"] or result.q0 per column, .messages (the driver's
    notes), and .to_pandas() when pandas is installed."""

    def __init__(self, csv, messages=""):
        text = csv.decode() if isinstance(csv, bytes) else csv
        lines = [line for line in text.splitlines() if line and not line.startswith("#")]
        self.messages = messages
        if not lines:
            self.columns = []
            self.data = numpy.zeros((0, 0))
            return
        self.columns = [name.strip() for name in lines[0].split(",")]
        if len(lines) > 1:
            self.data = numpy.loadtxt(io.StringIO("\n".join(lines[1:])), delimiter=",", ndmin=2)
        else:
            self.data = numpy.zeros((0, len(self.columns)))
        self._index = {name: i for i, name in enumerate(self.columns)}

    def __len__(self):
        return self.data.shape[0]

    def __contains__(self, name):
        return name in getattr(self, "_index", {})

    def __getitem__(self, name):
        try:
            return self.data[:, self._index[name]]
        except (KeyError, AttributeError):
            raise KeyError("%s: no such column; the columns: %s" % (name, ", ".join(self.columns))) from None

    def __getattr__(self, name):
        index = self.__dict__.get("_index", {})
        if name in index:
            return self.data[:, index[name]]
        raise AttributeError("%s: no such column or attribute; the columns: %s"
                             % (name, ", ".join(self.__dict__.get("columns", []))))

    @property
    def t(self):
        """The sample times."""
        return self["t"]

    def to_pandas(self):
        """The samples as a pandas DataFrame (needs pandas)."""
        try:
            import pandas
        except ImportError:
            raise ImportError("SimulationResult.to_pandas needs pandas (apt-get install python3-pandas); "
                              "the columns are NumPy arrays without it: result[name], result.data") from None
        return pandas.DataFrame(self.data, columns=self.columns)

    @property
    def dataframe(self):
        """to_pandas()."""
        return self.to_pandas()

    def __repr__(self):
        return "<kanegen.SimulationResult: %d samples of %d columns>" % (len(self), len(self.columns))

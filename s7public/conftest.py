import sys
from pathlib import Path

# the oracle and trace helpers of the regression
sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "tests"))

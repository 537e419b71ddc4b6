"""scikit-fem finite elements for charge-controlled soft dielectric plates."""

__all__: list[str] = []

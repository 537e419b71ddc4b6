"""FE-versus-analytic validation: the paper's figures with FE dots, and the CLI."""

__all__: list[str] = []

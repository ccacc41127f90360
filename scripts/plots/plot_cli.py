"""The command line of every plot script: its docstring's first paragraph as the description
and the rest (the example command, what it reads) after the arguments in --help."""
import argparse


def parser(doc):
    """An ArgumentParser for a plot script whose module docstring is `doc`."""
    head, _, rest = doc.partition("\n\n")
    return argparse.ArgumentParser(description=head, epilog=rest or None,
                                   formatter_class=argparse.RawDescriptionHelpFormatter)

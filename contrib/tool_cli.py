#!/usr/bin/python3
"""Conventions shared by the command-line tools of contrib/ (imported, not run).

Argument types that check a value when it is read, so that a wrong argument
stops a tool with a clear message and exit code 2 before anything runs, and
where results go: the folder named by --output, or doc/ with --doc, so that
running a benchmark never overwrites the repository's pages unless asked."""
import argparse
import os

ROOT = os.path.normpath(os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
DOC = os.path.join(ROOT, "doc")


def executable(path):
    """argparse type: a file that can be run; its absolute path (the tools run it from other directories)."""
    if not os.path.isfile(path):
        raise argparse.ArgumentTypeError(f"'{path}' does not exist or is not a file")
    if not os.access(path, os.X_OK):
        raise argparse.ArgumentTypeError(f"'{path}' is not executable")
    return os.path.abspath(path)


def existing_file(path):
    """argparse type: a file that exists."""
    if not os.path.isfile(path):
        raise argparse.ArgumentTypeError(f"'{path}' does not exist or is not a file")
    return path


def existing_directory(path):
    """argparse type: a directory that exists."""
    if not os.path.isdir(path):
        raise argparse.ArgumentTypeError(f"'{path}' does not exist or is not a directory")
    return path


def _number(convert, kind, is_valid, condition):
    """An argparse type: text converted by `convert` and accepted if is_valid(value)."""
    def check(text):
        try:
            value = convert(text)
        except ValueError:
            raise argparse.ArgumentTypeError(f"'{text}' is not {kind}") from None
        if not is_valid(value):
            raise argparse.ArgumentTypeError(f"{text} is not {condition}")
        return value
    return check


positive_int = _number(int, "a whole number", lambda v: v >= 1, ">= 1")
positive_float = _number(float, "a number", lambda v: v > 0, "> 0")


def setting(text):
    """argparse type: a parameter setting 'Section/Sub/Entry=value'."""
    path, sep, value = text.partition("=")
    if not sep or not path.strip() or "/" not in path or not value.strip():
        raise argparse.ArgumentTypeError(f"'{text}' is not of the form 'Section/Entry=value'")
    return text


def add_output_arguments(parser, default, doc_files, file_suffix=None):
    """Add --output FOLDER and --doc, which exclude each other.

    default: the folder, or None for the work directory (the tool then sets
    args.output to its --workdir). doc_files: the files --doc writes into doc/
    (for the help). With file_suffix (e.g. '.md'), --output may also name the
    result file itself, the form earlier versions of the tool took, so the
    commands written in doc/ keep working."""
    group = parser.add_mutually_exclusive_group()
    also = f" (or the {file_suffix} file itself)" if file_suffix else ""
    group.add_argument("--output", metavar="FOLDER", default=default,
                       help=f"folder that receives the results{also}; created if needed "
                            f"(default: {default or 'the work directory'})")
    group.add_argument("--doc", action="store_true",
                       help=f"write {', '.join(doc_files)} into doc/, the repository's pages, instead of --output")
    parser.set_defaults(output_file_suffix=file_suffix)


def check_output(parser, args):
    """Stop with a usage error if --output names an existing file where a folder is wanted."""
    if args.doc:
        return
    suffix = args.output_file_suffix
    if suffix and args.output.endswith(suffix):
        if os.path.isdir(args.output):
            parser.error(f"argument --output: '{args.output}' is a directory, not a {suffix} file")
    elif os.path.exists(args.output) and not os.path.isdir(args.output):
        parser.error(f"argument --output: '{args.output}' exists and is not a directory")


def parse_with_workdir(parser):
    """Parse the arguments of a tool with --workdir and add_output_arguments(parser, None, ...):
    --output defaults to the work directory, and is checked."""
    args = parser.parse_args()
    if args.output is None:
        args.output = args.workdir
    check_output(parser, args)
    return args


def destination(args, name):
    """Where the result file `name` goes (its folder created): doc/name with --doc, else
    --output itself when it names a file of name's kind, else name in the --output folder."""
    if args.doc:
        path = os.path.join(DOC, name)
    elif args.output_file_suffix and args.output.endswith(args.output_file_suffix) \
            and name.endswith(args.output_file_suffix):
        path = args.output
    else:
        path = os.path.join(args.output, name)
    path = os.path.abspath(path)
    os.makedirs(os.path.dirname(path), exist_ok=True)
    return path


def shown(path):
    """A path as a page should show it: relative to the repository when inside it."""
    path = os.path.abspath(path)
    return os.path.relpath(path, ROOT) if path.startswith(ROOT + os.sep) else path


def module_help(doc):
    """What a module of contrib/ does when run: --help (or no argument) prints its documentation."""
    parser = argparse.ArgumentParser(description=doc, formatter_class=argparse.RawDescriptionHelpFormatter,
                                     epilog="This file is a module for the other tools; it does nothing when run.")
    parser.parse_args()
    parser.print_help()


if __name__ == "__main__":
    module_help(__doc__)

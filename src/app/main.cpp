// emcontact command line (being written).
int main() { return 1; }
